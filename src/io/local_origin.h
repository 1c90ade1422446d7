#pragma once
/// \file local_origin.h
/// \brief Private: the last step of the PCD/PLY/XYZ readers. Coordinates were parsed in double;
///        drop non-finite points, choose (or take) the origin and store x_local = x_file - origin.

#include <pcl_ls3d/io/cloud_io.h>

#include <vector>

namespace pcl_ls3d {
namespace io {
namespace detail {

/// `xyz` holds 3 doubles per point of `cloud` (whose attributes are already set). Compacts the
/// cloud to the finite points, fills info.origin, bounds and counts. Sets points_in_file.
void
applyLocalOrigin(const std::vector<double>& xyz, pcl::PointCloud<PointLiDAR>& cloud,
                 CloudInfo& info, const LoadOptions& options);

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
