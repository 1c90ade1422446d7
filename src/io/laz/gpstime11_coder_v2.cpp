/// \file gpstime11_coder_v2.cpp
/// \brief GPSTIME11 version 2: the GPS time double, coded as its 64-bit pattern.
///
/// Pulses come at a steady rate, so the integer difference between consecutive time patterns is
/// nearly constant: it is coded as a multiple of the last difference plus a residual. Up to four
/// time sequences are tracked at once (files interleave flight lines or scanners); a time that
/// is far from the current sequence either switches to another one it is near or starts a new one
/// from its full 64 bits.

#include "integer_compressor.h"
#include "pointwise_items.h"

#include "io/las_format.h"

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

// Symbols of the multiplier model (after a non-zero difference).
constexpr std::int32_t kMultiMax = 500;    // multipliers 1..499 coded as such, 500 = at least 500
constexpr std::int32_t kMultiMinus = -10;  // -1..-9 coded as 501..509, 510 = -10 or less
constexpr std::uint32_t kUnchanged = kMultiMax - kMultiMinus + 1;     // 511
constexpr std::uint32_t kFullTime = kMultiMax - kMultiMinus + 2;      // 512; 513..515 switch
constexpr std::uint32_t kMultiSymbols = kMultiMax - kMultiMinus + 6;  // 516
// Symbols of the model after a zero difference: 0 unchanged, 1 a 32-bit difference, 2 a full
// time, 3..5 switch to sequence last + 1..3.
constexpr std::uint32_t kZeroDiffSymbols = 6;

class GpsTime11CoderV2 final : public PointwiseItemCoder
{
public:
  void
  init(const std::uint8_t* first) override;
  bool
  decode(ArithmeticDecoder& dec, std::uint8_t* out) override;
  void
  encode(ArithmeticEncoder& enc, const std::uint8_t* item) override;

private:
  /// Decodes within the current sequence; false when the symbol switches sequence instead.
  bool
  decodeInSequence(ArithmeticDecoder& dec);
  void
  decodeFromMultiplier(ArithmeticDecoder& dec, std::uint32_t multi);
  void
  decodeNewSequence(ArithmeticDecoder& dec);
  /// The other sequence within 32 bits of `t` (1..3 steps from the current), or 0.
  std::uint32_t
  nearSequence(std::int64_t t) const;
  void
  encodeInSequence(ArithmeticEncoder& enc, std::int64_t t);
  void
  encodeMultiplier(ArithmeticEncoder& enc, std::int32_t diff);
  void
  encodeNewSequence(ArithmeticEncoder& enc, std::int64_t t);
  /// After a multiplier of the extremes: adopt the difference once it has persisted.
  void
  countExtreme(std::int32_t diff);

  std::uint32_t last_ = 0, next_ = 0;
  std::int64_t time_[4] = {};
  std::int32_t diff_[4] = {};
  std::int32_t extremes_[4] = {};
  SymbolModel multi_{kMultiSymbols}, zero_diff_{kZeroDiffSymbols};
  IntegerCompressor ic_{32, 9};
};

/// The 64-bit difference as a 32-bit one when it fits.
bool
fits32(std::int64_t d, std::int32_t& d32)
{
  d32 = static_cast<std::int32_t>(d);
  return d == d32;
}

std::int64_t
difference(std::int64_t a, std::int64_t b)
{
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) - static_cast<std::uint64_t>(b));
}

std::int64_t
advance(std::int64_t t, std::int32_t d)
{
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(t) +
                                   static_cast<std::uint64_t>(static_cast<std::int64_t>(d)));
}

void
GpsTime11CoderV2::init(const std::uint8_t* first)
{
  last_ = next_ = 0;
  for (int i = 0; i < 4; ++i)
    time_[i] = diff_[i] = extremes_[i] = 0;
  multi_.reset();
  zero_diff_.reset();
  ic_.reset();
  time_[0] = las::get<std::int64_t>(first);
}

void
GpsTime11CoderV2::countExtreme(std::int32_t diff)
{
  if (++extremes_[last_] > 3) {
    diff_[last_] = diff;
    extremes_[last_] = 0;
  }
}

void
GpsTime11CoderV2::decodeNewSequence(ArithmeticDecoder& dec)
{
  next_ = (next_ + 1) & 3;
  const auto high = static_cast<std::uint32_t>(
      ic_.decompress(dec, static_cast<std::int32_t>(static_cast<std::uint64_t>(time_[last_]) >> 32), 8));
  const std::uint64_t low = dec.readInt();
  time_[next_] = static_cast<std::int64_t>((static_cast<std::uint64_t>(high) << 32) | low);
  last_ = next_;
  diff_[last_] = 0;
  extremes_[last_] = 0;
}

void
GpsTime11CoderV2::decodeFromMultiplier(ArithmeticDecoder& dec, std::uint32_t multi)
{
  const std::int32_t last_diff = diff_[last_];
  std::int32_t diff;
  if (multi == 0) {
    diff = ic_.decompress(dec, 0, 7);
    countExtreme(diff);
  } else if (multi < static_cast<std::uint32_t>(kMultiMax)) {
    const auto m = static_cast<std::int32_t>(multi);
    diff = ic_.decompress(dec, wrapMul(m, last_diff), m < 10 ? 2 : 3);
  } else if (multi == static_cast<std::uint32_t>(kMultiMax)) {
    diff = ic_.decompress(dec, wrapMul(kMultiMax, last_diff), 4);
    countExtreme(diff);
  } else {
    const std::int32_t m = kMultiMax - static_cast<std::int32_t>(multi);  // -1 .. -10
    if (m > kMultiMinus) {
      diff = ic_.decompress(dec, wrapMul(m, last_diff), 5);
    } else {
      diff = ic_.decompress(dec, wrapMul(kMultiMinus, last_diff), 6);
      countExtreme(diff);
    }
  }
  time_[last_] = advance(time_[last_], diff);
}

bool
GpsTime11CoderV2::decodeInSequence(ArithmeticDecoder& dec)
{
  if (diff_[last_] == 0) {
    const std::uint32_t sym = dec.decodeSymbol(zero_diff_);
    if (sym == 1) {
      diff_[last_] = ic_.decompress(dec, 0, 0);
      time_[last_] = advance(time_[last_], diff_[last_]);
      extremes_[last_] = 0;
    } else if (sym == 2) {
      decodeNewSequence(dec);
    } else if (sym > 2) {
      last_ = (last_ + sym - 2) & 3;
      return false;
    }
    return true;
  }
  const std::uint32_t multi = dec.decodeSymbol(multi_);
  if (multi == 1) {
    time_[last_] = advance(time_[last_], ic_.decompress(dec, diff_[last_], 1));
    extremes_[last_] = 0;
  } else if (multi < kUnchanged) {
    decodeFromMultiplier(dec, multi);
  } else if (multi == kFullTime) {
    decodeNewSequence(dec);
  } else if (multi > kFullTime) {
    last_ = (last_ + multi - kFullTime) & 3;
    return false;
  }
  return true;
}

bool
GpsTime11CoderV2::decode(ArithmeticDecoder& dec, std::uint8_t* out)
{
  // An encoder switches sequence at most once per record (to one within 32 bits of the time), so
  // a second switch can only come from a corrupt stream.
  if (!decodeInSequence(dec) && !decodeInSequence(dec))
    return false;
  las::put<std::int64_t>(out, time_[last_]);
  return true;
}

std::uint32_t
GpsTime11CoderV2::nearSequence(std::int64_t t) const
{
  std::int32_t d32;
  for (std::uint32_t i = 1; i < 4; ++i)
    if (fits32(difference(t, time_[(last_ + i) & 3]), d32))
      return i;
  return 0;
}

void
GpsTime11CoderV2::encodeNewSequence(ArithmeticEncoder& enc, std::int64_t t)
{
  const auto bits = static_cast<std::uint64_t>(t);
  ic_.compress(enc, static_cast<std::int32_t>(static_cast<std::uint64_t>(time_[last_]) >> 32),
               static_cast<std::int32_t>(bits >> 32), 8);
  enc.writeInt(static_cast<std::uint32_t>(bits));
  next_ = (next_ + 1) & 3;
  last_ = next_;
  diff_[last_] = 0;
  extremes_[last_] = 0;
}

void
GpsTime11CoderV2::encodeMultiplier(ArithmeticEncoder& enc, std::int32_t diff)
{
  const std::int32_t last_diff = diff_[last_];
  const float ratio = static_cast<float>(diff) / static_cast<float>(last_diff);
  const std::int32_t multi = truncateToInt(ratio >= 0 ? ratio + 0.5 : ratio - 0.5);
  if (multi == 1) {
    enc.encodeSymbol(multi_, 1);
    ic_.compress(enc, last_diff, diff, 1);
    extremes_[last_] = 0;
  } else if (multi > 0 && multi < kMultiMax) {
    enc.encodeSymbol(multi_, static_cast<std::uint32_t>(multi));
    ic_.compress(enc, wrapMul(multi, last_diff), diff, multi < 10 ? 2 : 3);
  } else if (multi >= kMultiMax) {
    enc.encodeSymbol(multi_, kMultiMax);
    ic_.compress(enc, wrapMul(kMultiMax, last_diff), diff, 4);
    countExtreme(diff);
  } else if (multi < 0 && multi > kMultiMinus) {
    enc.encodeSymbol(multi_, static_cast<std::uint32_t>(kMultiMax - multi));
    ic_.compress(enc, wrapMul(multi, last_diff), diff, 5);
  } else if (multi < 0) {
    enc.encodeSymbol(multi_, static_cast<std::uint32_t>(kMultiMax - kMultiMinus));
    ic_.compress(enc, wrapMul(kMultiMinus, last_diff), diff, 6);
    countExtreme(diff);
  } else {
    enc.encodeSymbol(multi_, 0);
    ic_.compress(enc, 0, diff, 7);
    countExtreme(diff);
  }
}

void
GpsTime11CoderV2::encodeInSequence(ArithmeticEncoder& enc, std::int64_t t)
{
  const bool zero_diff = diff_[last_] == 0;
  if (t == time_[last_]) {
    enc.encodeSymbol(zero_diff ? zero_diff_ : multi_, zero_diff ? 0 : kUnchanged);
    return;
  }
  std::int32_t d32;
  if (fits32(difference(t, time_[last_]), d32)) {
    if (zero_diff) {
      enc.encodeSymbol(zero_diff_, 1);
      ic_.compress(enc, 0, d32, 0);
      diff_[last_] = d32;
      extremes_[last_] = 0;
    } else {
      encodeMultiplier(enc, d32);
    }
  } else {
    enc.encodeSymbol(zero_diff ? zero_diff_ : multi_, zero_diff ? 2 : kFullTime);
    encodeNewSequence(enc, t);
  }
  time_[last_] = t;
}

void
GpsTime11CoderV2::encode(ArithmeticEncoder& enc, const std::uint8_t* item)
{
  const std::int64_t t = las::get<std::int64_t>(item);
  std::int32_t d32;
  if (t != time_[last_] && !fits32(difference(t, time_[last_]), d32)) {
    if (const std::uint32_t i = nearSequence(t)) {
      // Switch to the sequence the time is near, then code it there.
      const bool zero_diff = diff_[last_] == 0;
      enc.encodeSymbol(zero_diff ? zero_diff_ : multi_, zero_diff ? i + 2 : kFullTime + i);
      last_ = (last_ + i) & 3;
    }
  }
  encodeInSequence(enc, t);
}

}  // namespace

std::unique_ptr<PointwiseItemCoder>
makeGpsTime11CoderV2()
{
  return std::make_unique<GpsTime11CoderV2>();
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
