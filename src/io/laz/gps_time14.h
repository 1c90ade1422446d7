#pragma once
/// \file gps_time14.h
/// \brief Private: the GPS-time layer of POINT14. Times are coded as integer differences of their
///        IEEE bit patterns, predicted from the previous difference times a small multiplier, in
///        up to four interleaved sequences (so that two strips or channels alternating in time
///        stay cheap). One object per scanner-channel context.

#include "arithmetic_decoder.h"
#include "arithmetic_encoder.h"
#include "integer_compressor.h"

#include <array>
#include <cstdint>

namespace pcl_ls3d {
namespace io {
namespace laz {

class GpsTime14
{
public:
  GpsTime14();

  /// Starts a chunk (or a new channel context) whose last time is `first` (bit pattern).
  void
  start(std::uint64_t first);

  /// The next time's bit pattern.
  std::uint64_t
  decode(ArithmeticDecoder& dec);
  void
  encode(ArithmeticEncoder& enc, std::uint64_t time);

private:
  std::uint64_t
  decodeFromZeroDifference(ArithmeticDecoder& dec, bool& switched);
  std::uint64_t
  decodeFromMultiplier(ArithmeticDecoder& dec, bool& switched);
  std::int32_t
  decodeScaledDifference(ArithmeticDecoder& dec, std::int32_t multi);
  void
  decodeNewSequence(ArithmeticDecoder& dec);

  bool
  encodeWithZeroDifference(ArithmeticEncoder& enc, std::uint64_t time);
  bool
  encodeWithMultiplier(ArithmeticEncoder& enc, std::uint64_t time);
  void
  encodeScaledDifference(ArithmeticEncoder& enc, std::int32_t diff);
  void
  encodeNewSequence(ArithmeticEncoder& enc, std::uint64_t time);
  /// 1–3 when `time` is within 32 bits of another sequence's last time, else 0.
  unsigned
  nearSequence(std::uint64_t time) const;
  /// Counts a prediction far off; the fourth in a row becomes the sequence's new difference.
  void
  countExtreme(std::int32_t diff);

  SymbolModel multi_, zero_diff_;
  IntegerCompressor ic_;
  unsigned last_ = 0, next_ = 0;
  std::array<std::uint64_t, 4> time_{};
  std::array<std::int32_t, 4> diff_{};
  std::array<std::int32_t, 4> extreme_{};
};

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
