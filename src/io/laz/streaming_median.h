#pragma once
/// \file streaming_median.h
/// \brief Private: LASzip's running estimate of the typical X / Y step, the middle of five kept
///        values. It is part of the format: coder and decoder must update it identically.

#include <algorithm>
#include <array>
#include <cstdint>

namespace pcl_ls3d {
namespace io {
namespace laz {

/// \brief Five sorted values; each new one displaces the largest or the smallest in turn (which
///        one depends on where the previous value fell), and the middle one is the prediction.
class StreamingMedian5
{
public:
  std::int32_t
  get() const
  {
    return v_[2];
  }

  void
  add(std::int32_t v)
  {
    const std::int32_t middle = v_[2];
    if (drop_largest_) {
      insertSorted(v, 0, 4);  // v_[4] falls out
      drop_largest_ = v < middle;
    } else {
      std::copy(v_.begin() + 1, v_.end(), v_.begin());  // v_[0] falls out
      insertSorted(v, 0, 4);
      drop_largest_ = !(middle < v);
    }
  }

private:
  /// Inserts v into the sorted v_[first, last) and shifts the larger ones up one place (the value
  /// at `last` is overwritten).
  void
  insertSorted(std::int32_t v, int first, int last)
  {
    int i = last;
    while (i > first && v < v_[i - 1]) {
      v_[i] = v_[i - 1];
      --i;
    }
    v_[i] = v;
  }

  std::array<std::int32_t, 5> v_{};
  bool drop_largest_ = true;
};

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
