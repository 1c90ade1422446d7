/// \file gps_time14.cpp
/// \brief The GPS-time layer of POINT14 (see gps_time14.h). Differences wrap in 32 or 64 bits as
///        the format does; nothing here overflows a signed type.

#include "gps_time14.h"

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

// Multiplier symbols: 0 (no prediction), 1 … 499 and 500 (or more), 501 … 510 for −1 … −10 (or
// less), then 511 "new sequence" and 512 … 514 "switch to sequence last + 1 … 3".
constexpr std::int32_t kMultiMax = 500;
constexpr std::int32_t kMultiMin = -10;
constexpr std::uint32_t kCodeNewSequence = kMultiMax - kMultiMin + 1;
constexpr std::uint32_t kMultiSymbols = kMultiMax - kMultiMin + 5;

// A time whose last difference was 0 codes: 0 a 32-bit difference, 1 new sequence, 2–4 switch.
constexpr std::uint32_t kZeroDiffSymbols = 5;

bool
fits32(std::int64_t v)
{
  return v == static_cast<std::int32_t>(v);
}

std::int64_t
difference(std::uint64_t a, std::uint64_t b)
{
  return static_cast<std::int64_t>(a - b);
}

/// multi · diff, wrapping in 32 bits as LASzip's int arithmetic does.
std::int32_t
scaled(std::int32_t multi, std::int32_t diff)
{
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(multi) * static_cast<std::uint32_t>(diff));
}

/// LASzip's multiplier: the single-precision ratio, rounded half away from zero (in double).
/// Beyond ±1000 every value codes the same way, so the ratio is clamped before the cast.
std::int32_t
quantizeMultiplier(std::int32_t diff, std::int32_t last_diff)
{
  const double ratio = static_cast<float>(diff) / static_cast<float>(last_diff);
  if (ratio >= 1000.0)
    return 1000;
  if (ratio <= -1000.0)
    return -1000;
  return static_cast<std::int32_t>(ratio >= 0 ? ratio + 0.5 : ratio - 0.5);
}

}  // namespace

GpsTime14::GpsTime14() : multi_(kMultiSymbols), zero_diff_(kZeroDiffSymbols), ic_(32, 9)
{}

void
GpsTime14::start(std::uint64_t first)
{
  multi_.reset();
  zero_diff_.reset();
  ic_.reset();
  last_ = next_ = 0;
  time_ = {first, 0, 0, 0};
  diff_ = {};
  extreme_ = {};
}

void
GpsTime14::countExtreme(std::int32_t diff)
{
  if (++extreme_[last_] > 3) {
    diff_[last_] = diff;
    extreme_[last_] = 0;
  }
}

// ---- decoding ----

std::uint64_t
GpsTime14::decode(ArithmeticDecoder& dec)
{
  // A writer switches sequence at most once per time; garbage may ask for more, so the hops are
  // bounded instead of following them recursively.
  for (int hop = 0; hop < 4; ++hop) {
    bool switched = false;
    const std::uint64_t t =
        diff_[last_] == 0 ? decodeFromZeroDifference(dec, switched) : decodeFromMultiplier(dec, switched);
    if (!switched)
      return t;
  }
  return time_[last_];
}

std::uint64_t
GpsTime14::decodeFromZeroDifference(ArithmeticDecoder& dec, bool& switched)
{
  const std::uint32_t sym = dec.decodeSymbol(zero_diff_);
  if (sym == 0) {
    diff_[last_] = ic_.decompress(dec, 0, 0);
    time_[last_] += static_cast<std::uint64_t>(static_cast<std::int64_t>(diff_[last_]));
    extreme_[last_] = 0;
  } else if (sym == 1) {
    decodeNewSequence(dec);
  } else {
    last_ = (last_ + sym - 1) & 3;
    switched = true;
  }
  return time_[last_];
}

std::uint64_t
GpsTime14::decodeFromMultiplier(ArithmeticDecoder& dec, bool& switched)
{
  const std::uint32_t sym = dec.decodeSymbol(multi_);
  std::int32_t diff = 0;
  if (sym == 1) {
    diff = ic_.decompress(dec, diff_[last_], 1);
    extreme_[last_] = 0;
  } else if (sym < kCodeNewSequence) {
    diff = decodeScaledDifference(dec, static_cast<std::int32_t>(sym));
  } else if (sym == kCodeNewSequence) {
    decodeNewSequence(dec);
    return time_[last_];
  } else {
    last_ = (last_ + sym - kCodeNewSequence) & 3;
    switched = true;
    return time_[last_];
  }
  time_[last_] += static_cast<std::uint64_t>(static_cast<std::int64_t>(diff));
  return time_[last_];
}

std::int32_t
GpsTime14::decodeScaledDifference(ArithmeticDecoder& dec, std::int32_t sym)
{
  const std::int32_t last = diff_[last_];
  std::int32_t diff;
  if (sym == 0) {
    diff = ic_.decompress(dec, 0, 7);
    countExtreme(diff);
  } else if (sym < kMultiMax) {
    diff = ic_.decompress(dec, scaled(sym, last), sym < 10 ? 2 : 3);
  } else if (sym == kMultiMax) {
    diff = ic_.decompress(dec, scaled(kMultiMax, last), 4);
    countExtreme(diff);
  } else if (kMultiMax - sym > kMultiMin) {
    diff = ic_.decompress(dec, scaled(kMultiMax - sym, last), 5);
  } else {
    diff = ic_.decompress(dec, scaled(kMultiMin, last), 6);
    countExtreme(diff);
  }
  return diff;
}

void
GpsTime14::decodeNewSequence(ArithmeticDecoder& dec)
{
  const auto high =
      static_cast<std::uint32_t>(ic_.decompress(dec, static_cast<std::int32_t>(time_[last_] >> 32), 8));
  const std::uint32_t low = dec.readInt();
  next_ = (next_ + 1) & 3;
  time_[next_] = (static_cast<std::uint64_t>(high) << 32) | low;
  last_ = next_;
  diff_[last_] = 0;
  extreme_[last_] = 0;
}

// ---- encoding ----

void
GpsTime14::encode(ArithmeticEncoder& enc, std::uint64_t time)
{
  // After a switch the time is within 32 bits of the chosen sequence, so the second pass codes it.
  for (int pass = 0; pass < 2; ++pass) {
    const bool coded =
        diff_[last_] == 0 ? encodeWithZeroDifference(enc, time) : encodeWithMultiplier(enc, time);
    if (coded)
      break;
  }
  time_[last_] = time;
}

unsigned
GpsTime14::nearSequence(std::uint64_t time) const
{
  for (unsigned i = 1; i < 4; ++i)
    if (fits32(difference(time, time_[(last_ + i) & 3])))
      return i;
  return 0;
}

bool
GpsTime14::encodeWithZeroDifference(ArithmeticEncoder& enc, std::uint64_t time)
{
  const std::int64_t diff = difference(time, time_[last_]);
  if (fits32(diff)) {
    enc.encodeSymbol(zero_diff_, 0);
    ic_.compress(enc, 0, static_cast<std::int32_t>(diff), 0);
    diff_[last_] = static_cast<std::int32_t>(diff);
    extreme_[last_] = 0;
    return true;
  }
  if (const unsigned other = nearSequence(time)) {
    enc.encodeSymbol(zero_diff_, other + 1);
    last_ = (last_ + other) & 3;
    return false;
  }
  enc.encodeSymbol(zero_diff_, 1);
  encodeNewSequence(enc, time);
  return true;
}

bool
GpsTime14::encodeWithMultiplier(ArithmeticEncoder& enc, std::uint64_t time)
{
  const std::int64_t diff64 = difference(time, time_[last_]);
  if (!fits32(diff64)) {
    if (const unsigned other = nearSequence(time)) {
      enc.encodeSymbol(multi_, kCodeNewSequence + other);
      last_ = (last_ + other) & 3;
      return false;
    }
    enc.encodeSymbol(multi_, kCodeNewSequence);
    encodeNewSequence(enc, time);
    return true;
  }
  encodeScaledDifference(enc, static_cast<std::int32_t>(diff64));
  return true;
}

void
GpsTime14::encodeScaledDifference(ArithmeticEncoder& enc, std::int32_t diff)
{
  const std::int32_t last = diff_[last_];
  const std::int32_t multi = quantizeMultiplier(diff, last);
  if (multi == 1) {
    enc.encodeSymbol(multi_, 1);
    ic_.compress(enc, last, diff, 1);
    extreme_[last_] = 0;
  } else if (multi > 1 && multi < kMultiMax) {
    enc.encodeSymbol(multi_, static_cast<std::uint32_t>(multi));
    ic_.compress(enc, scaled(multi, last), diff, multi < 10 ? 2 : 3);
  } else if (multi >= kMultiMax) {
    enc.encodeSymbol(multi_, kMultiMax);
    ic_.compress(enc, scaled(kMultiMax, last), diff, 4);
    countExtreme(diff);
  } else if (multi < 0 && multi > kMultiMin) {
    enc.encodeSymbol(multi_, static_cast<std::uint32_t>(kMultiMax - multi));
    ic_.compress(enc, scaled(multi, last), diff, 5);
  } else if (multi < 0) {
    enc.encodeSymbol(multi_, static_cast<std::uint32_t>(kMultiMax - kMultiMin));
    ic_.compress(enc, scaled(kMultiMin, last), diff, 6);
    countExtreme(diff);
  } else {
    enc.encodeSymbol(multi_, 0);
    ic_.compress(enc, 0, diff, 7);
    countExtreme(diff);
  }
}

void
GpsTime14::encodeNewSequence(ArithmeticEncoder& enc, std::uint64_t time)
{
  ic_.compress(enc, static_cast<std::int32_t>(time_[last_] >> 32), static_cast<std::int32_t>(time >> 32), 8);
  enc.writeInt(static_cast<std::uint32_t>(time));
  next_ = (next_ + 1) & 3;
  last_ = next_;
  diff_[last_] = 0;
  extreme_[last_] = 0;
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
