#pragma once
/// \file xyz_io.h
/// \brief ASCII XYZ reader and writer (full coordinates parsed in double).
///
/// Reading. Separators: spaces, tabs, commas or semicolons (mixed allowed). Blank lines and comment
/// lines starting with '#' or '//' are skipped. Columns are mapped, in order of precedence, by
///  1. LoadOptions::xyz_columns, e.g. "x,y,z,intensity,classification" ("_" or "skip" ignores one);
///  2. a header line: the first non-blank line, commented or not, whose tokens name x, y and z
///     (e.g. "X Y Z Intensity Classification" or CloudCompare's "//X,Y,Z,R,G,B");
///  3. otherwise columns 1–3 are x y z and further columns are ignored.
/// Recognised names (case-insensitive): x y z; intensity | i; classification | class | label;
/// point_source_id | psid | source_id; gps_time | time | t; return_number; number_of_returns.
/// Other names are ignored. A data line with too few columns or a token that is not a number is an
/// error naming the line.
///
/// Writing. A header comment "# x y z intensity classification point_source_id gps_time
/// return_number number_of_returns" and one line per point, space separated; the reader maps the
/// columns back from that header. Numbers keep full precision (the shortest text that reads back
/// as the same double) unless SaveOptions::xyz_decimals asks for fixed decimals.
/// Errors quote at most 40 characters of the offending text, with its line and column.

#include <pcl_ls3d/io/cloud_io.h>

#include <istream>
#include <string>

namespace pcl_ls3d {
namespace io {

/// Parses ASCII XYZ text from a stream (see the file comment for the column rules).
bool
readXyz(std::istream& in, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info, std::string& error,
        const LoadOptions& options = {});

/// Writes ASCII XYZ text (no overwrite check here; saveCloud() does it).
bool
writeXyzFile(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
             std::string& error, const SaveOptions& options = {});

}  // namespace io
}  // namespace pcl_ls3d
