#pragma once
/// \file segments_file.h
/// \brief SEGMENTS.pcd, the output of pcl_ls3d_segment, in the form plain PCL code reads:
///        `pcl::io::loadPCDFile(path, cloud)` with `pcl::PointCloud<pcl::PointXYZRGBL>` gives
///        every input point, in input order, with its segment label and colour.
///
/// Layout (binary PCD v0.7): fields x y z (FLOAT32, local coordinates), rgba (UINT32, a colour
/// per segment, pcl::PointXYZRGBL's layout), label (UINT32, segment id + 1, 0 = in no segment),
/// and, when the segments have classes (IMRG), classification (UINT8, the LAS code of the
/// segment's object class, segmentation::lasCode(); 0 = in no segment). PointXYZRGBL loads
/// skip the extra field; io::loadCloud() reads it as the points' classification, so
/// pcl_ls3d_convert writes the object classes into a LAS file's classification.
/// Coordinates are local: file coordinate = x + origin. A float cannot hold a UTM or Lambert-93
/// coordinate to the centimetre, and PCL's point types have float x, y, z only (a FLOAT64 x is
/// not found by loadPCDFile into PointXYZRGBL: every point would load as (0, 0, 0)). The origin
/// is written in the header as a comment line that PCL skips:
///   # pcl_ls3d origin X Y Z
/// (io::pcdOriginLine(), %.17g, so the double comes back exactly); readSegmentsOrigin() parses it
/// back, and io::loadCloud() reads the file in the input's frame (local floats, CloudInfo::origin
/// = this origin, as for the LAS input). A second comment line (io::kPcdSegmentsMarker) says the labels
/// are segment ids; when the input declared a CRS, a third (io::pcdCrsLine(), "# pcl_ls3d crs
/// WKT") records it, so that pictures get their unit and a LAS converted from the file its CRS.
/// Points whose input coordinates were not finite keep their place with NaN
/// coordinates and label 0, so that the file lines up with the input point for point (is_dense
/// false then).

#include <pcl/PointIndices.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// \brief Where the loaded points sit in the input file.
struct InputLayout
{
  std::size_t points_in_file = 0;                    ///< input points, finite or not
  std::vector<std::size_t> nonfinite;                ///< file indices of the dropped points, ascending
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< file coordinate = local + origin
  std::string crs_wkt;  ///< the input's CRS (OGC WKT), recorded in the header; empty: none
};

/// \brief Writes SEGMENTS.pcd.
/// \param[in] path output file
/// \param[in] cloud the finite input points in input order (local coordinates), as loaded
/// \param[in] segments indices into \a cloud
/// \param[in] layout where \a cloud's points sit in the input file
/// \param[in] segment_codes per segment: LAS code of its class; empty: no classification field
/// \return false with a one-line reason (counts that do not add up, write failure)
bool
saveSegmentsPcd(const std::string& path, const pcl::PointCloud<pcl::PointXYZ>& cloud,
                const std::vector<pcl::PointIndices>& segments, const InputLayout& layout, std::string& error,
                const std::vector<std::uint8_t>& segment_codes = {});

/// \brief True when \a path's header carries io::kPcdSegmentsMarker (pcd_io.h): its labels are
///        segment ids, never classes (pcl_ls3d_segment -evaluate refuses such a file as its own
///        reference before reading it; io::loadCloud() reports it as CloudInfo::segments_file).
bool
isSegmentsFile(const std::string& path);

/// \brief The origin from the first "# pcl_ls3d origin" header line of \a path; false if the
///        file has none, that line is malformed (io::loadCloud refuses such a file too), or the
///        file cannot be read.
bool
readSegmentsOrigin(const std::string& path, Eigen::Vector3d& origin);

}  // namespace evaluation
}  // namespace pcl_ls3d
