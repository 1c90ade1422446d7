#pragma once
/// \file pcl_formats.h
/// \brief Private: PCD and PLY written via pcl::PCLPointCloud2 (PLY through PCL's writer, PCD
///        with PCL's header plus the CRS line, pcd_io.h), so that FLOAT64 x/y/z (georeferenced
///        clouds) keep double precision. Reading: pcd_io.h, ply_io.h.

#include <pcl_ls3d/io/cloud_io.h>

#include <string>

namespace pcl_ls3d {
namespace io {
namespace detail {

/// Writes every PointLiDAR field; x y z are FLOAT64 when origin != 0, else FLOAT32.
bool
writePclFile(const std::string& path, const std::string& format, const pcl::PointCloud<PointLiDAR>& cloud,
             const Eigen::Vector3d& origin, std::string& error, const SaveOptions& options);

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
