/// \file local_origin.cpp
/// \brief The auto-origin rule (cloud_io.h) and the shared last step of the double-precision readers.

#include "local_origin.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace io {

Eigen::Vector3d
chooseOrigin(const Eigen::Vector3d& min_file, const Eigen::Vector3d& max_file)
{
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(min_file[k]) || !std::isfinite(max_file[k]))
      continue;
    if (std::max(std::abs(min_file[k]), std::abs(max_file[k])) >= 1e4)
      origin[k] = std::round(0.5 * (min_file[k] + max_file[k]));
  }
  return origin;
}

namespace detail {

void
applyLocalOrigin(const std::vector<double>& xyz, pcl::PointCloud<PointLiDAR>& cloud,
                 CloudInfo& info, const LoadOptions& options)
{
  const std::size_t n = cloud.size();
  info.points_in_file = n;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  std::size_t kept = 0;
  std::vector<std::size_t> keep;
  keep.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    if (!p.allFinite())
      continue;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    keep.push_back(i);
  }
  kept = keep.size();
  info.points_dropped_nonfinite = n - kept;
  info.points_loaded = kept;
  if (kept > 0) {
    info.min_file = lo;
    info.max_file = hi;
  }
  info.origin = options.use_origin ? options.origin : chooseOrigin(info.min_file, info.max_file);
  for (std::size_t j = 0; j < kept; ++j) {
    const std::size_t i = keep[j];
    PointLiDAR p = cloud[i];
    p.x = static_cast<float>(xyz[3 * i] - info.origin[0]);
    p.y = static_cast<float>(xyz[3 * i + 1] - info.origin[1]);
    p.z = static_cast<float>(xyz[3 * i + 2] - info.origin[2]);
    cloud[j] = p;
  }
  cloud.resize(kept);  // also sets width = kept, height = 1
  cloud.is_dense = true;
}

}  // namespace detail

}  // namespace io
}  // namespace pcl_ls3d
