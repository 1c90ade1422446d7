/// \file arithmetic_encoder.cpp
/// \brief Carry propagation and the final flush of the LASzip arithmetic encoder.

#include "arithmetic_encoder.h"

namespace pcl_ls3d {
namespace io {
namespace laz {

void
ArithmeticEncoder::propagateCarry()
{
  // A carry never runs past the first byte: the interval's base starts at 0 and only the bytes
  // written since can be 0xFF.
  std::size_t p = out_.size();
  while (p > 0 && out_[p - 1] == 0xFF)
    out_[--p] = 0;
  if (p > 0)
    ++out_[p - 1];
}

const std::vector<std::uint8_t>&
ArithmeticEncoder::finish()
{
  // LASzip's flush: pick a value inside the final interval that needs as few bytes as possible,
  // then pad with two or three zero bytes so the decoder's four-byte look-ahead stays in range.
  bool another_byte = true;
  if (length_ > 2 * kMinLength) {
    add(kMinLength);
    length_ = kMinLength >> 1;
  } else {
    add(kMinLength >> 1);
    length_ = kMinLength >> 9;
    another_byte = false;
  }
  renormalise();
  out_.push_back(0);
  out_.push_back(0);
  if (another_byte)
    out_.push_back(0);
  return out_;
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
