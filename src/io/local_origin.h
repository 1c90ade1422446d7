#pragma once
/// \file local_origin.h
/// \brief Private: the last step of the PCD/PLY/XYZ readers. Coordinates were parsed in double;
///        drop non-finite points, choose (or take) the origin and store x_local = x_file - origin.

#include <pcl_ls3d/io/cloud_io.h>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace detail {

/// `xyz` holds 3 doubles per point of `cloud` (whose attributes are already set), stored values
/// with x_file = xyz + file_origin (a PCD's recorded origin, else zero). Compacts the cloud to the
/// finite points, fills info.origin, file bounds and counts. Sets points_in_file. False (cloud
/// cleared) when a local coordinate would not fit in a float (fitsInFloat).
bool
applyLocalOrigin(const std::vector<double>& xyz, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
                 const LoadOptions& options, std::string& error,
                 const Eigen::Vector3d& file_origin = Eigen::Vector3d::Zero());

/// True when every x_file in [min_file, max_file] minus `origin` is a finite float; else false
/// with a one-line reason (a file whose coordinates span 1e300 cannot be held in local floats).
bool
fitsInFloat(const Eigen::Vector3d& min_file, const Eigen::Vector3d& max_file, const Eigen::Vector3d& origin,
            std::string& error);

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
