#pragma once
/// \file integer_compressor.h
/// \brief Private: LASzip's integer compressor. It codes the difference between a value and its
///        prediction as k (the number of bits the difference needs, one adaptive model per
///        context) followed by the difference's bits within that range (adaptive models for the
///        high bits up to `bits_high`, raw bits below). Every item coder is built on it.

#include "arithmetic_decoder.h"
#include "arithmetic_encoder.h"

#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace laz {

class IntegerCompressor
{
public:
  /// `bits`: width of the values (wrap-around modulo 2^bits); `range`: alternatively the number
  /// of distinct values; `contexts`: independent model sets chosen per call.
  explicit IntegerCompressor(std::uint32_t bits = 16, std::uint32_t contexts = 1, std::uint32_t bits_high = 8,
                             std::uint32_t range = 0);

  /// Back to the initial models, as at the start of every chunk (or layer).
  void
  reset();

  std::int32_t
  decompress(ArithmeticDecoder& dec, std::int32_t pred, std::uint32_t context = 0);
  void
  compress(ArithmeticEncoder& enc, std::int32_t pred, std::int32_t real, std::uint32_t context = 0);

  /// k of the last value coded: the number of bits its corrector needed (a context for others).
  std::uint32_t
  k() const
  {
    return k_;
  }

private:
  std::int32_t
  readCorrector(ArithmeticDecoder& dec, SymbolModel& bits_model);
  void
  writeCorrector(ArithmeticEncoder& enc, std::int32_t c, SymbolModel& bits_model);

  std::uint32_t contexts_, bits_high_;
  std::uint32_t corr_bits_ = 0, corr_range_ = 0;
  std::int32_t corr_min_ = 0, corr_max_ = 0;
  std::uint32_t k_ = 0;
  std::vector<SymbolModel> bits_;       ///< per context: k
  BitModel corrector0_;                 ///< k == 0: the difference is 0 or 1
  std::vector<SymbolModel> corrector_;  ///< [k]: the high bits of a k-bit difference (k >= 1)
};

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
