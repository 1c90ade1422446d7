#pragma once
/// \file pcd_header.h
/// \brief Private: the PCD header as written and what follows from it (record sizes, WIDTH x
///        HEIGHT = POINTS). Nothing here allocates in proportion to a count in the file.

#include "point_fields.h"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace detail {

enum class PcdBody
{
  Ascii,
  Binary,
  Compressed
};

/// The header as written, then what follows from it.
struct PcdHeader
{
  std::vector<std::string> names;
  std::vector<std::size_t> sizes;
  std::vector<char> kinds;
  std::vector<std::uint64_t> counts;
  std::uint64_t width = 0, height = 0, points = 0;
  bool has_width = false, has_height = false, has_points = false;
  PcdBody body = PcdBody::Ascii;
  std::size_t data_offset = 0;
  std::vector<Scalar> types;
  std::size_t record = 0;   ///< bytes per point (binary)
  std::size_t packed = 0;   ///< bytes per point without "_" padding fields (binary_compressed)
  std::size_t values = 0;   ///< values per point (ASCII)
  bool has_origin = false;  ///< a "# pcl_ls3d origin" line was read (pcd_io.h)
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< x_file = stored value + origin
  std::string crs_wkt;           ///< the first "# pcl_ls3d crs" line's WKT (pcd_io.h), empty if none
  bool segments_marker = false;  ///< a kPcdSegmentsMarker line was read: label is no class
};

/// Parses and checks the header; h.data_offset is the first byte after the DATA line.
bool
parsePcdHeader(const std::uint8_t* data, std::size_t size, PcdHeader& h, std::string& error);

/// Sets `error` to "PCD " + message; returns false.
bool
pcdFail(std::string& error, const std::string& message);

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
