#pragma once
// Private helpers shared by the generators: chunked, thread-count-independent sampling.

#include <pcl_ls3d/point_types.h>
#include <pcl_ls3d/synth/random.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstdint>

namespace pcl_ls3d {
namespace synth {
namespace detail {

/// Points per random stream block; each block has its own Random(seed, stream, block).
constexpr std::size_t kBlock = 1u << 15;

/// Calls f(i, rng) for i in [0, n), in parallel over blocks of kBlock indices, each block with
/// its own stream, so the result does not depend on the number of threads.
template <typename F>
void
forEachBlocked(std::size_t n, std::uint32_t seed, std::uint32_t stream, F&& f)
{
  const std::int64_t blocks = static_cast<std::int64_t>((n + kBlock - 1) / kBlock);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t b = 0; b < blocks; ++b) {
    Random rng(seed, stream, static_cast<std::uint32_t>(b));
    const std::size_t end = std::min(n, static_cast<std::size_t>(b + 1) * kBlock);
    for (std::size_t i = static_cast<std::size_t>(b) * kBlock; i < end; ++i)
      f(i, rng);
  }
}

inline PointLiDAR
makePoint(const Eigen::Vector3d& p)
{
  return PointLiDAR(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
}

}  // namespace detail
}  // namespace synth
}  // namespace pcl_ls3d
