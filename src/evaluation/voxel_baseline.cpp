/// \file voxel_baseline.cpp
/// \brief Voxel-grid segmentation with a target segment count.

#include <pcl_ls3d/evaluation/voxel_baseline.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace pcl_ls3d {
namespace evaluation {
namespace {

bool
finite(const pcl::PointXYZ& p)
{
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

/// Cell key of every finite point (−1 for the others), and the number of distinct keys.
std::size_t
cellKeys(const pcl::PointCloud<pcl::PointXYZ>& cloud, double size, std::vector<std::int64_t>& key)
{
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  for (const auto& p : cloud.points)
    if (finite(p))
      lo = lo.cwiseMin(p.getVector3fMap().cast<double>());
  key.assign(cloud.size(), -1);
  std::unordered_map<std::int64_t, int> seen;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!finite(cloud[i]))
      continue;
    const Eigen::Vector3d c = (cloud[i].getVector3fMap().cast<double>() - lo) / size;
    // 21 bits per axis: enough for 2 M cells along each axis.
    const auto ix = static_cast<std::int64_t>(std::min(c.x(), 2097151.0));
    const auto iy = static_cast<std::int64_t>(std::min(c.y(), 2097151.0));
    const auto iz = static_cast<std::int64_t>(std::min(c.z(), 2097151.0));
    key[i] = (ix << 42) | (iy << 21) | iz;
    seen.emplace(key[i], 0);
  }
  return seen.size();
}

}  // namespace

std::vector<pcl::PointIndices>
voxelSegments(const pcl::PointCloud<pcl::PointXYZ>& cloud, double size)
{
  std::vector<std::int64_t> key;
  cellKeys(cloud, size, key);
  std::unordered_map<std::int64_t, std::size_t> slot;
  std::vector<pcl::PointIndices> out;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (key[i] < 0)
      continue;
    const auto it = slot.emplace(key[i], out.size()).first;
    if (it->second == out.size())
      out.emplace_back();
    out[it->second].indices.push_back(static_cast<int>(i));
  }
  return out;
}

std::vector<pcl::PointIndices>
voxelSegmentsWithCount(const pcl::PointCloud<pcl::PointXYZ>& cloud, std::size_t target, double& size)
{
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : cloud.points)
    if (finite(p)) {
      lo = lo.cwiseMin(p.getVector3fMap().cast<double>());
      hi = hi.cwiseMax(p.getVector3fMap().cast<double>());
    }
  const double extent = (hi - lo).maxCoeff();
  if (!(extent > 0.0) || target == 0) {
    size = std::max(extent, 1.0) * 2.0;
    return voxelSegments(cloud, size);
  }
  // Count falls as the edge grows: bracket [extent / 2e6, 2 extent] and bisect on log size.
  double small = extent / 2e6, large = 2.0 * extent;
  std::vector<std::int64_t> key;
  double best = large;
  std::size_t best_error = std::numeric_limits<std::size_t>::max();
  for (int step = 0; step < 40; ++step) {
    const double mid = std::sqrt(small * large);
    const std::size_t count = cellKeys(cloud, mid, key);
    const std::size_t err = count > target ? count - target : target - count;
    if (err < best_error) {
      best_error = err;
      best = mid;
    }
    if (100 * err <= target)
      break;
    (count > target ? small : large) = mid;
  }
  size = best;
  return voxelSegments(cloud, size);
}

}  // namespace evaluation
}  // namespace pcl_ls3d
