/// \file gpstime11_coder_v1.cpp
/// \brief GPSTIME11 version 1: the GPS time's 64-bit pattern, coded as a multiple (0–509) of the
///        last integer difference plus a residual, or written whole when the difference does not
///        fit in 32 bits. One time sequence only (version 2 tracks four).

#include "integer_compressor.h"
#include "pointwise_items.h"

#include "io/las_format.h"

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

constexpr std::uint32_t kMultiSymbols = 512;
constexpr std::int32_t kMultiLargest = kMultiSymbols - 3;  // 509: "509 or more"
constexpr std::uint32_t kFullTime = kMultiSymbols - 2;     // 510
constexpr std::uint32_t kUnchanged = kMultiSymbols - 1;    // 511
// After a zero difference: 0 unchanged, 1 a 32-bit difference, 2 a full time.
constexpr std::uint32_t kZeroDiffSymbols = 3;

std::int64_t
advance(std::int64_t t, std::int32_t d)
{
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(t) +
                                   static_cast<std::uint64_t>(static_cast<std::int64_t>(d)));
}

class GpsTime11CoderV1 final : public PointwiseItemCoder
{
public:
  void
  init(const std::uint8_t* first) override
  {
    diff_ = extremes_ = 0;
    multi_.reset();
    zero_diff_.reset();
    ic_.reset();
    time_ = las::get<std::int64_t>(first);
  }

  bool
  decode(ArithmeticDecoder& dec, std::uint8_t* out) override;
  void
  encode(ArithmeticEncoder& enc, const std::uint8_t* item) override;

private:
  /// The residual's prediction and context for multiplier `multi` (0–509).
  void
  predictionFor(std::int32_t multi, std::int32_t& pred, std::uint32_t& context) const;
  /// What a multiplier other than 1 does to the remembered difference.
  void
  afterMultiplier(std::int32_t multi, std::int32_t diff);

  std::int64_t time_ = 0;
  std::int32_t diff_ = 0, extremes_ = 0;
  SymbolModel multi_{kMultiSymbols}, zero_diff_{kZeroDiffSymbols};
  IntegerCompressor ic_{32, 6};
};

void
GpsTime11CoderV1::predictionFor(std::int32_t multi, std::int32_t& pred, std::uint32_t& context) const
{
  if (multi == 1) {
    pred = diff_;
    context = 1;
  } else if (multi == 0) {
    pred = diff_ / 4;
    context = 2;
  } else {
    pred = wrapMul(multi, diff_);
    context = multi < 10 ? 3 : (multi < 50 ? 4 : 5);
  }
}

void
GpsTime11CoderV1::afterMultiplier(std::int32_t multi, std::int32_t diff)
{
  if (multi == 1) {
    diff_ = diff;
    extremes_ = 0;
  } else if ((multi == 0 || multi == kMultiLargest) && ++extremes_ > 3) {
    diff_ = diff;
    extremes_ = 0;
  }
}

bool
GpsTime11CoderV1::decode(ArithmeticDecoder& dec, std::uint8_t* out)
{
  if (diff_ == 0) {
    const std::uint32_t sym = dec.decodeSymbol(zero_diff_);
    if (sym == 1) {
      diff_ = ic_.decompress(dec, 0, 0);
      time_ = advance(time_, diff_);
    } else if (sym == 2) {
      time_ = static_cast<std::int64_t>(dec.readInt64());
    }
  } else {
    const std::uint32_t sym = dec.decodeSymbol(multi_);
    if (sym < kFullTime) {
      const auto multi = static_cast<std::int32_t>(sym);
      std::int32_t pred;
      std::uint32_t context;
      predictionFor(multi, pred, context);
      const std::int32_t diff = ic_.decompress(dec, pred, context);
      afterMultiplier(multi, diff);
      time_ = advance(time_, diff);
    } else if (sym == kFullTime) {
      time_ = static_cast<std::int64_t>(dec.readInt64());
    }
  }
  las::put<std::int64_t>(out, time_);
  return true;
}

void
GpsTime11CoderV1::encode(ArithmeticEncoder& enc, const std::uint8_t* item)
{
  const std::int64_t t = las::get<std::int64_t>(item);
  const bool zero_diff = diff_ == 0;
  if (t == time_) {
    enc.encodeSymbol(zero_diff ? zero_diff_ : multi_, zero_diff ? 0 : kUnchanged);
    return;
  }
  const auto d64 =
      static_cast<std::int64_t>(static_cast<std::uint64_t>(t) - static_cast<std::uint64_t>(time_));
  const auto diff = static_cast<std::int32_t>(d64);
  if (d64 != diff) {
    enc.encodeSymbol(zero_diff ? zero_diff_ : multi_, zero_diff ? 2 : kFullTime);
    enc.writeInt64(static_cast<std::uint64_t>(t));
  } else if (zero_diff) {
    enc.encodeSymbol(zero_diff_, 1);
    ic_.compress(enc, 0, diff, 0);
    diff_ = diff;
  } else {
    const float ratio = static_cast<float>(diff) / static_cast<float>(diff_);
    std::int32_t multi = truncateToInt(ratio + 0.5f);
    multi = multi >= kMultiLargest ? kMultiLargest : (multi <= 0 ? 0 : multi);
    enc.encodeSymbol(multi_, static_cast<std::uint32_t>(multi));
    std::int32_t pred;
    std::uint32_t context;
    predictionFor(multi, pred, context);
    ic_.compress(enc, pred, diff, context);
    afterMultiplier(multi, diff);
  }
  time_ = t;
}

}  // namespace

std::unique_ptr<PointwiseItemCoder>
makeGpsTime11CoderV1()
{
  return std::make_unique<GpsTime11CoderV1>();
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
