/// \file local_origin.cpp
/// \brief The auto-origin rule (cloud_io.h) and the shared last step of the double-precision readers.

#include "local_origin.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

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
      origin[k] = std::round(0.5 * min_file[k] + 0.5 * max_file[k]);  // no overflow near 1e308
  }
  return origin;
}

namespace detail {

bool
fitsInFloat(const Eigen::Vector3d& min_file, const Eigen::Vector3d& max_file, const Eigen::Vector3d& origin,
            std::string& error)
{
  const double reach =
      std::max((min_file - origin).cwiseAbs().maxCoeff(), (max_file - origin).cwiseAbs().maxCoeff());
  if (reach <= static_cast<double>(std::numeric_limits<float>::max()))
    return true;
  std::ostringstream s;
  s << "coordinates reach " << reach << " from the local origin, beyond what a float holds";
  error = s.str();
  return false;
}

bool
applyLocalOrigin(const std::vector<double>& xyz, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
                 const LoadOptions& options, std::string& error, const Eigen::Vector3d& file_origin)
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
    if (!p.allFinite()) {
      info.nonfinite_indices.push_back(i);
      continue;
    }
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    keep.push_back(i);
  }
  kept = keep.size();
  info.points_dropped_nonfinite = n - kept;
  info.points_loaded = kept;
  if (kept > 0) {
    info.min_file = lo + file_origin;
    info.max_file = hi + file_origin;
  }
  info.origin = options.use_origin ? options.origin : chooseOrigin(info.min_file, info.max_file);
  if (kept > 0 && !fitsInFloat(info.min_file, info.max_file, info.origin, error)) {
    cloud.clear();
    return false;
  }
  // x_local = stored + (file_origin - origin), as the LAS reader adds (offset - origin): when
  // the origin is the recorded one the stored floats come back bit for bit.
  const Eigen::Vector3d shift = file_origin - info.origin;
  for (std::size_t j = 0; j < kept; ++j) {
    const std::size_t i = keep[j];
    PointLiDAR p = cloud[i];
    p.x = static_cast<float>(xyz[3 * i] + shift[0]);
    p.y = static_cast<float>(xyz[3 * i + 1] + shift[1]);
    p.z = static_cast<float>(xyz[3 * i + 2] + shift[2]);
    cloud[j] = p;
  }
  cloud.resize(kept);
  cloud.width = static_cast<std::uint32_t>(kept);
  cloud.height = 1;
  cloud.is_dense = true;
  return true;
}

}  // namespace detail

}  // namespace io
}  // namespace pcl_ls3d
