#pragma once
/// \file parallel.h
/// \brief When the engine's loops run on several OpenMP threads.

#include <cstddef>

namespace pcl_ls3d {

/// \brief Loops over fewer items than this run on one thread: starting the team and its
///        barrier cost more than the work (docs/DECISIONS.md).
constexpr std::size_t kMinParallelItems = 4096;

/// \brief True when a loop over `items` is worth a thread team (for `#pragma omp ... if(...)`).
constexpr bool
worthParallel(std::size_t items)
{
  return items >= kMinParallelItems;
}

}  // namespace pcl_ls3d
