// Regular thinning of the source observations (declared in surface_matching_core.h).
#include <pcl_ls3d/adjustment/surface_matching_core.h>
#include <pcl_ls3d/common/voxel_index.h>

#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <numeric>
#include <unordered_set>

namespace pcl_ls3d {

namespace {

using VoxelKey = std::array<std::int64_t, 3>;

struct VoxelKeyHash
{
  std::size_t
  operator()(const VoxelKey& k) const
  {
    const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };  // wraps, no UB
    return static_cast<std::size_t>(u(k[0]) * 73856093u ^ u(k[1]) * 19349663u ^ u(k[2]) * 83492791u);
  }
};

std::vector<int>
everyIndex(std::size_t n)
{
  std::vector<int> all(n);
  std::iota(all.begin(), all.end(), 0);
  return all;
}

}  // namespace

std::vector<int>
thinByVoxel(const std::vector<Eigen::Vector3d>& points, double step)
{
  if (!(step > 0.0))
    return everyIndex(points.size());
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points)
    if (p.allFinite())
      box.extend(p);
  // Voxels finer than the coordinates resolve would only merge identical points: keep all
  // (voxel coordinates would saturate there and merge everything instead).
  const double reach = box.isEmpty() ? 0.0 : box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).maxCoeff();
  if (box.isEmpty() || reach / step >= static_cast<double>(kVoxelCoordinateLimit))
    return everyIndex(points.size());
  // Full voxel coordinates (the same voxels as ever, about the coordinate origin): no wrapped
  // keys merging far-apart voxels.
  std::vector<int> kept;
  kept.reserve(points.size() / 4);
  std::unordered_set<VoxelKey, VoxelKeyHash> seen;
  seen.reserve(points.size() / 2);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d& p = points[i];
    const VoxelKey key{voxelCoordinate(p.x(), step), voxelCoordinate(p.y(), step),
                       voxelCoordinate(p.z(), step)};
    if (seen.insert(key).second)
      kept.push_back(static_cast<int>(i));
  }
  return kept;
}

}  // namespace pcl_ls3d
