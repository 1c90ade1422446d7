#include <pcl_ls3d/common/voxel_index.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

namespace pcl_ls3d {

CloudSpacing
cloudSpacing(const std::vector<Eigen::Vector3d>& points, int axis)
{
  Eigen::AlignedBox3d box;
  std::size_t n = 0;
  for (const Eigen::Vector3d& p : points)
    if (p.allFinite()) {
      box.extend(p);
      ++n;
    }
  CloudSpacing out;
  if (n < 2)
    return out;
  const Eigen::Vector3d e = box.sizes();
  const double areas[3] = {e.y() * e.z(), e.x() * e.z(), e.x() * e.y()};  // normal x, y, z
  out.normal_axis =
      axis >= 0 && axis < 3 ? axis : static_cast<int>(std::max_element(areas, areas + 3) - areas);
  out.spacing = std::sqrt(areas[out.normal_axis] / static_cast<double>(n));
  if (!(out.spacing > 0.0)) {  // collinear points: spacing along the line
    out.spacing = e.maxCoeff() / static_cast<double>(n);
    return out;
  }
  // The box overstates the footprint of a rotated or irregular cloud (a lake, a corridor):
  // refine with the area of the occupied cells, twice.
  const int a = (out.normal_axis + 1) % 3, b = (out.normal_axis + 2) % 3;
  for (int pass = 0; pass < 2; ++pass)
    out.spacing = std::sqrt(static_cast<double>(occupiedCells(points, a, b, out.spacing)) * out.spacing *
                            out.spacing / static_cast<double>(n));
  return out;
}

std::size_t
occupiedCells(const std::vector<Eigen::Vector3d>& points, int a, int b, double cell)
{
  std::unordered_set<std::uint64_t> cells;
  for (const Eigen::Vector3d& p : points)
    if (p.allFinite())
      cells.insert(planCellKey(planCellCoordinate(p[a], cell), planCellCoordinate(p[b], cell)));
  return cells.size();
}

std::int64_t
planCellCoordinate(double x, double cell)
{
  constexpr std::int64_t kLimit = std::numeric_limits<std::int32_t>::max();
  return std::clamp<std::int64_t>(voxelCoordinate(x, cell), -kLimit, kLimit);
}

std::uint64_t
planCellKey(std::int64_t u, std::int64_t v)
{
  const auto saturate = [](std::int64_t c) {
    constexpr std::int64_t kLimit = std::numeric_limits<std::int32_t>::max();
    return static_cast<std::uint32_t>(static_cast<std::int32_t>(std::clamp(c, -kLimit, kLimit)));
  };
  return static_cast<std::uint64_t>(saturate(u)) << 32 | saturate(v);
}

std::int64_t
voxelCoordinate(double x, double cell)
{
  const double c = std::floor(x / cell);
  if (!(c == c))
    return 0;
  const auto limit = static_cast<double>(kVoxelCoordinateLimit);
  return static_cast<std::int64_t>(std::max(-limit, std::min(c, limit)));
}

VoxelIndex::VoxelIndex(const std::vector<Eigen::Vector3d>& points, double cell)
    : points_(points), cell_(cell > 0.0 ? cell : 1.0)
{
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].allFinite()) {
      voxels_[key(points[i])].push_back(static_cast<int>(i));
      ++stored_;
    }
}

std::int64_t
VoxelIndex::key(std::int64_t x, std::int64_t y, std::int64_t z)
{
  // 21 bits per axis (±1e6 cells), wrapped: collisions only merge far-apart voxels' lists,
  // which the distance test below filters.
  const std::int64_t m = (1 << 21) - 1;
  return ((x & m) << 42) | ((y & m) << 21) | (z & m);
}

std::int64_t
VoxelIndex::key(const Eigen::Vector3d& p) const
{
  return key(voxelCoordinate(p.x(), cell_), voxelCoordinate(p.y(), cell_), voxelCoordinate(p.z(), cell_));
}

void
VoxelIndex::radiusSearch(const Eigen::Vector3d& q, double radius, std::vector<int>& out) const
{
  out.clear();
  if (!q.allFinite() || !(radius >= 0.0))
    return;
  std::int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = voxelCoordinate(q[a] - radius, cell_);
    hi[a] = voxelCoordinate(q[a] + radius, cell_);
  }
  const double r2 = radius * radius;
  const double span = static_cast<double>(hi[0] - lo[0] + 1) * static_cast<double>(hi[1] - lo[1] + 1) *
                      static_cast<double>(hi[2] - lo[2] + 1);
  if (span > static_cast<double>(voxels_.size())) {  // fewer stored voxels than to visit
    for (const auto& v : voxels_)
      for (const int i : v.second)
        if ((points_[static_cast<std::size_t>(i)] - q).squaredNorm() <= r2)
          out.push_back(i);
    return;
  }
  for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
      for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
        const auto it = voxels_.find(key(x, y, z));
        if (it == voxels_.end())
          continue;
        for (const int i : it->second)
          if ((points_[static_cast<std::size_t>(i)] - q).squaredNorm() <= r2)
            out.push_back(i);
      }
}

void
VoxelIndex::nearestK(const Eigen::Vector3d& q, int k, std::vector<int>& out) const
{
  out.clear();
  if (k <= 0 || !q.allFinite() || voxels_.empty())
    return;
  // Grow the radius until k points lie within it (a point within r is certainly found).
  const std::size_t stored = stored_;
  std::vector<int> found;
  for (double r = cell_;; r *= 2.0) {
    radiusSearch(q, r, found);
    if (static_cast<int>(found.size()) >= k || found.size() == stored)
      break;
  }
  std::sort(found.begin(), found.end(), [&](int a, int b) {
    const double da = (points_[static_cast<std::size_t>(a)] - q).squaredNorm();
    const double db = (points_[static_cast<std::size_t>(b)] - q).squaredNorm();
    return da < db || (da == db && a < b);
  });
  if (static_cast<int>(found.size()) > k)
    found.resize(static_cast<std::size_t>(k));
  out = std::move(found);
}

}  // namespace pcl_ls3d
