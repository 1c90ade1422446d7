#pragma once
/// \file pcl_formats.h
/// \brief Private: PCD and PLY through PCL's own readers/writers via pcl::PCLPointCloud2, so that
///        FLOAT64 x/y/z (georeferenced clouds) are read and written in double.

#include <pcl_ls3d/io/cloud_io.h>

#include <string>

namespace pcl_ls3d {
namespace io {
namespace detail {

/// `format` is "pcd" or "ply". Fields mapped: x y z (any numeric type, read in double), intensity,
/// gps_time, point_source_id, classification (or label when there is no classification),
/// return_number, number_of_returns. Other fields are ignored.
bool
readPclFile(const std::string& path, const std::string& format,
            pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info, std::string& error,
            const LoadOptions& options);

/// Writes every PointLiDAR field; x y z are FLOAT64 when origin != 0, else FLOAT32.
bool
writePclFile(const std::string& path, const std::string& format,
             const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
             std::string& error, const SaveOptions& options);

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
