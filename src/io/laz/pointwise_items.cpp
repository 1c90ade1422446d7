/// \file pointwise_items.cpp
/// \brief The pieces the pointwise item coders share: the streaming median and the return
///        contexts (see pointwise_items.h).

#include "pointwise_items.h"

#include <algorithm>

namespace pcl_ls3d {
namespace io {
namespace laz {

void
StreamingMedian5::add(std::int32_t x)
{
  // The window stays sorted; the end that is dropped alternates: after a value at or above the
  // median the smallest goes next, after a value at or below it the largest.
  if (drop_largest_) {
    drop_largest_ = x < v_[2];
    auto pos = std::upper_bound(v_.begin(), v_.end() - 1, x);
    std::copy_backward(pos, v_.end() - 1, v_.end());
    *pos = x;
  } else {
    drop_largest_ = !(v_[2] < x);
    auto pos = std::lower_bound(v_.begin() + 1, v_.end(), x);
    std::copy(v_.begin() + 1, pos, v_.begin());
    *(pos - 1) = x;
  }
}

std::uint32_t
point10ReturnContext(std::uint32_t n, std::uint32_t r)
{
  // Rows: number of returns n; columns: return number r (both 3-bit fields, so 0–7).
  static const std::uint8_t kContext[8][8] = {
      {15, 14, 13, 12, 11, 10, 9, 8},  {14, 0, 1, 3, 6, 10, 10, 9},   {13, 1, 2, 4, 7, 11, 11, 10},
      {12, 3, 4, 5, 8, 12, 12, 11},    {11, 6, 7, 8, 9, 13, 13, 12},  {10, 10, 11, 12, 13, 14, 14, 13},
      {9, 10, 11, 12, 13, 14, 15, 14}, {8, 9, 10, 11, 12, 13, 14, 15}};
  return kContext[n & 7][r & 7];
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
