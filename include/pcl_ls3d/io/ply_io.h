#pragma once
/// \file ply_io.h
/// \brief PLY reader (ascii, binary_little_endian, binary_big_endian) on a memory buffer. Writing
///        goes through PCL's PLYWriter (binary) or pcl_ls3d's ASCII writer (saveCloud); a CRS is
///        recorded in a "comment pcl_ls3d crs WKT" header line.
///
/// Only the vertex element is read: elements before it (rare) are skipped, elements after it
/// (faces, a Stanford scanner's range_grid, a camera) are not read at all, so a range grid of
/// 512 x 400 cells around 40 256 vertices gives 40 256 points, none of them "dropped". The header
/// is checked before anything is allocated: counts are plain non-negative decimal integers, types
/// are the PLY names (char uchar short ushort int uint float double, or int8 ... float64), list
/// counts are integers, and the vertex count is checked against the bytes present (binary: the
/// smallest record size; ASCII: two bytes per value). Vertex properties mapped: x y z (any type, read
/// in double), intensity, gps_time, point_source_id, classification (or label),
/// return_number, number_of_returns; lists and other properties are skipped.

#include <pcl_ls3d/io/cloud_io.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace pcl_ls3d {
namespace io {

/// \brief The header line that records a CRS, without a newline: "comment pcl_ls3d crs WKT",
///        line breaks of the WKT made spaces (the PLY counterpart of pcdCrsLine(); readPly()
///        gives it back as CloudInfo::file_crs_wkt, other readers skip it as a comment).
std::string
plyCrsLine(const std::string& wkt);

/// Parses an in-memory PLY file into local coordinates (cloud_io.h describes the origin rule).
/// Never reads outside [data, data + size); returns false with a one-line reason.
bool
readPly(const std::uint8_t* data, std::size_t size, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
        std::string& error, const LoadOptions& options = {});

}  // namespace io
}  // namespace pcl_ls3d
