// Regular thinning of the source observations (declared in surface_matching_core.h).
#include <pcl_ls3d/adjustment/surface_matching_core.h>

#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace pcl_ls3d {

std::vector<int>
thinByVoxel(const std::vector<Eigen::Vector3d>& points, double step)
{
  std::vector<int> kept;
  kept.reserve(step > 0.0 ? points.size() / 4 : points.size());
  if (!(step > 0.0)) {
    for (std::size_t i = 0; i < points.size(); ++i)
      kept.push_back(static_cast<int>(i));
    return kept;
  }
  std::unordered_set<std::uint64_t> seen;
  seen.reserve(points.size() / 2);
  for (std::size_t i = 0; i < points.size(); ++i) {
    // 21 bits per axis (wraps for huge extents, which only merges far-apart voxels rarely).
    std::uint64_t key = 0;
    for (int a = 0; a < 3; ++a)
      key = (key << 21) |
            (static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(points[i][a] / step))) &
             0x1FFFFF);
    if (seen.insert(key).second)
      kept.push_back(static_cast<int>(i));
  }
  return kept;
}

}  // namespace pcl_ls3d
