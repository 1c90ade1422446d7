/// \file integer_compressor.cpp
/// \brief LASzip's corrector coding (see integer_compressor.h).

#include "integer_compressor.h"

#include <limits>

namespace pcl_ls3d {
namespace io {
namespace laz {

IntegerCompressor::IntegerCompressor(std::uint32_t bits, std::uint32_t contexts, std::uint32_t bits_high,
                                     std::uint32_t range)
    : contexts_(contexts), bits_high_(bits_high)
{
  if (range != 0) {
    corr_range_ = range;
    while (range != 0) {
      range >>= 1;
      ++corr_bits_;
    }
    if (corr_range_ == (1u << (corr_bits_ - 1)))
      --corr_bits_;
    corr_min_ = -static_cast<std::int32_t>(corr_range_ / 2);
    corr_max_ = static_cast<std::int32_t>(corr_min_ + corr_range_ - 1);
  } else if (bits != 0 && bits < 32) {
    corr_bits_ = bits;
    corr_range_ = 1u << bits;
    corr_min_ = -static_cast<std::int32_t>(corr_range_ / 2);
    corr_max_ = static_cast<std::int32_t>(corr_min_ + corr_range_ - 1);
  } else {
    corr_bits_ = 32;
    corr_range_ = 0;
    corr_min_ = std::numeric_limits<std::int32_t>::min();
    corr_max_ = std::numeric_limits<std::int32_t>::max();
  }
  bits_.assign(contexts_, SymbolModel(corr_bits_ + 1));
  corrector_.reserve(corr_bits_ + 1);
  corrector_.emplace_back(2);  // unused slot 0 (k == 0 uses corrector0_)
  for (std::uint32_t i = 1; i <= corr_bits_; ++i)
    corrector_.emplace_back(i <= bits_high_ ? (1u << i) : (1u << bits_high_));
}

void
IntegerCompressor::reset()
{
  for (SymbolModel& m : bits_)
    m.reset();
  corrector0_ = BitModel();
  for (SymbolModel& m : corrector_)
    m.reset();
  k_ = 0;
}

std::int32_t
IntegerCompressor::decompress(ArithmeticDecoder& dec, std::int32_t pred, std::uint32_t context)
{
  // Modular arithmetic in uint32: the format wraps, and signed overflow would be undefined.
  std::int64_t real = static_cast<std::int64_t>(pred) + readCorrector(dec, bits_[context]);
  if (real < 0)
    real += corr_range_;
  else if (corr_range_ != 0 && real >= static_cast<std::int64_t>(corr_range_))
    real -= corr_range_;
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(real));
}

std::int32_t
IntegerCompressor::readCorrector(ArithmeticDecoder& dec, SymbolModel& bits_model)
{
  k_ = dec.decodeSymbol(bits_model);
  if (k_ == 0)
    return static_cast<std::int32_t>(dec.decodeBit(corrector0_));
  if (k_ >= 32)
    return corr_min_;
  std::uint32_t c;
  if (k_ <= bits_high_) {
    c = dec.decodeSymbol(corrector_[k_]);
  } else {
    const std::uint32_t k1 = k_ - bits_high_;
    c = dec.decodeSymbol(corrector_[k_]);
    c = (c << k1) | dec.readBits(k1);
  }
  // c is in [0, 2^k): the upper half are the positive differences, the lower half the negative.
  if (c >= (1u << (k_ - 1)))
    return static_cast<std::int32_t>(c + 1);
  return static_cast<std::int32_t>(c - ((1u << k_) - 1));
}

void
IntegerCompressor::compress(ArithmeticEncoder& enc, std::int32_t pred, std::int32_t real,
                            std::uint32_t context)
{
  std::int64_t corr = static_cast<std::int64_t>(real) - pred;
  if (corr < corr_min_)
    corr += corr_range_;
  else if (corr > corr_max_)
    corr -= corr_range_;
  writeCorrector(enc, static_cast<std::int32_t>(corr), bits_[context]);
}

void
IntegerCompressor::writeCorrector(ArithmeticEncoder& enc, std::int32_t c, SymbolModel& bits_model)
{
  const std::uint32_t uc = static_cast<std::uint32_t>(c);
  std::uint32_t c1 = (c <= 0) ? 0u - uc : uc - 1;
  k_ = 0;
  while (c1 != 0) {
    c1 >>= 1;
    ++k_;
  }
  enc.encodeSymbol(bits_model, k_);
  if (k_ == 0) {
    enc.encodeBit(corrector0_, uc);
    return;
  }
  if (k_ >= 32)
    return;
  std::uint32_t v = (c < 0) ? uc + ((1u << k_) - 1) : uc - 1;
  if (k_ <= bits_high_) {
    enc.encodeSymbol(corrector_[k_], v);
  } else {
    const std::uint32_t k1 = k_ - bits_high_;
    const std::uint32_t low = v & ((1u << k1) - 1);
    enc.encodeSymbol(corrector_[k_], v >> k1);
    enc.writeBits(k1, low);
  }
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
