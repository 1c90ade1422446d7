#pragma once
/// \file pcd_io.h
/// \brief PCD reader (v0.5–0.7; DATA ascii, binary, binary_compressed) on a memory buffer, so the
///        same code serves files, tests and the fuzzer. Writing: PCL's PCDWriter makes the
///        header, savePcdBinaryWithComments() adds the comment lines (saveCloud in cloud_io.h).
///
/// The header is checked before anything is allocated: FIELDS, SIZE, TYPE (F 4/8, U and I
/// 1/2/4/8) and COUNT (optional, >= 1) must agree; WIDTH x HEIGHT must equal POINTS; counts are
/// plain decimal integers. Then the header's claim is checked against the bytes present: binary
/// needs POINTS x record size bytes; binary_compressed needs its compressed block and an
/// uncompressed size equal to POINTS x record size (and no more than LZF can expand); ASCII needs
/// at least two bytes per value. A file that claims a billion points but holds ten fails there,
/// with one line saying so, before any allocation. Fields mapped: see cloud_io.h / pcl_formats.h.
///
/// Recorded origin. A PCD that stores local float coordinates (pcl_ls3d_segment's SEGMENTS.pcd:
/// a float cannot hold projected coordinates) records its origin in a header comment, which PCL
/// skips:
///   # pcl_ls3d origin X Y Z
/// file coordinate = stored value + origin. readPcd() then returns the stored values as the
/// local coordinates with CloudInfo::origin = CloudInfo::file_origin = that origin, as a LAS
/// file's offset is applied (with LoadOptions::use_origin the points are moved to the forced
/// origin instead). A malformed origin line, or a second one, fails the header.
///
/// Recorded CRS. Such a PCD may also carry the coordinate reference of those file coordinates
/// (SEGMENTS.pcd of a georeferenced LAS) in one comment line holding OGC WKT:
///   # pcl_ls3d crs PROJCS["RGF93 v1 / Lambert-93",...]
/// readPcd() returns it as CloudInfo::file_crs_wkt (the first such line; not interpreted here).
///
/// Segments. pcl_ls3d_segment's SEGMENTS.pcd stores segment ids in PCL's `label` field, which
/// other PCDs use for classes; the header line kPcdSegmentsMarker says so, and readPcd() then
/// leaves `label` out of the classification (CloudInfo::segments_file; a `classification`
/// field, the object classes, is read as usual).

#include <pcl_ls3d/io/cloud_io.h>

#include <pcl/PCLPointCloud2.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace pcl_ls3d {
namespace io {

/// Header comment line of a SEGMENTS.pcd: its label field holds segment ids, never classes.
constexpr const char* kPcdSegmentsMarker = "# pcl_ls3d segments: label = segment id + 1, not a class";

/// \brief Is \a line (a PCD header line, with or without "\r" or trailing spaces) the
///        kPcdSegmentsMarker line? The reader and evaluation::isSegmentsFile() both ask this.
bool
isPcdSegmentsMarkerLine(std::string_view line);

/// Parses an in-memory PCD file into local coordinates (cloud_io.h describes the origin rule).
/// Never reads outside [data, data + size); returns false with a one-line reason.
bool
readPcd(const std::uint8_t* data, std::size_t size, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
        std::string& error, const LoadOptions& options = {});

/// \brief The header line that records `origin`, without a newline: "# pcl_ls3d origin X Y Z"
///        with %.17g, so the doubles come back exactly.
std::string
pcdOriginLine(const Eigen::Vector3d& origin);

/// \brief The header line that records a CRS, without a newline: "# pcl_ls3d crs WKT", line
///        breaks of the WKT made spaces.
std::string
pcdCrsLine(const std::string& wkt);

/// \brief Writes \a cloud as a binary PCD (fields packed, no padding) with \a comments (whole
///        "# ..." lines, each ending in a newline; may be empty) after PCL's first header line,
///        e.g. pcdCrsLine(). The stored values are what \a cloud holds.
/// \return false with a one-line reason (the file cannot be written, too few data bytes)
bool
savePcdBinaryWithComments(const std::string& path, const pcl::PCLPointCloud2& cloud,
                          const std::string& comments, std::string& error);

/// \brief Writes \a cloud as a binary PCD (fields packed, no padding) whose header records
///        \a origin (pcdOriginLine(), after PCL's first header line) and then \a comments (whole
///        "# ..." lines, each ending in a newline; may be empty). The stored floats are local
///        coordinates, file coordinate = stored + origin: io::loadCloud() reads the file in that
///        frame, pcl::io::loadPCDFile() reads the floats as they are.
/// \return false with a one-line reason (the file cannot be written, too few data bytes)
bool
savePcdBinaryWithOrigin(const std::string& path, const pcl::PCLPointCloud2& cloud,
                        const Eigen::Vector3d& origin, const std::string& comments, std::string& error);

/// What parsePcdOriginLine() found in a header line.
enum class PcdOriginLine
{
  NotOrigin,  ///< another line (or another comment)
  Origin,     ///< an origin line; the origin was set
  Malformed   ///< "# pcl_ls3d origin" not followed by exactly three finite numbers
};

/// \brief Reads the origin from a PCD header line written by pcdOriginLine(); `origin` is left
///        unchanged unless the result is PcdOriginLine::Origin.
PcdOriginLine
parsePcdOriginLine(std::string_view line, Eigen::Vector3d& origin);

}  // namespace io
}  // namespace pcl_ls3d
