#pragma once
/// \file ascii_writers.h
/// \brief Private: numbers as the shortest text that reads back as the same value (std::to_chars),
///        and the ASCII PCD and PLY writers built on it. PCL 1.13's ASCII writers print a fixed
///        number of digits (6 for PLY doubles, the caller's precision for PCD), which loses
///        georeferenced coordinates; these keep every bit.

#include <pcl_ls3d/point_types.h>

#include <pcl/point_cloud.h>

#include <Eigen/Core>

#include <string>

namespace pcl_ls3d {
namespace io {
namespace detail {

/// Appends `v`: the shortest text that reads back as exactly `v`, or `decimals` fixed decimals
/// (0-17) when decimals >= 0.
void
appendNumber(std::string& out, double v, int decimals = -1);

/// Appends the shortest text that reads back as exactly the float `v`.
void
appendNumber(std::string& out, float v);

/// ASCII PCD / PLY with every PointLiDAR field: x y z are x_local + origin in double (FLOAT64 /
/// "double") when origin != 0, else the local floats. PCD: \a comments (whole "# ..." lines)
/// after the first header line. False when the file cannot be written.
bool
writePcdAscii(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud,
              const Eigen::Vector3d& origin, const std::string& comments = "");

/// PLY: \a comments (whole "comment ..." lines) after the format line.
bool
writePlyAscii(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud,
              const Eigen::Vector3d& origin, const std::string& comments = "");

/// Inserts \a comments (whole "comment ..." lines) after the format line of the PLY file at
/// \a path (PCL's PLYWriter takes none): the file is copied through a temporary file beside it.
bool
insertPlyComments(const std::string& path, const std::string& comments);

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
