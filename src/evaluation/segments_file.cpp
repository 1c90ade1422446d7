/// \file segments_file.cpp
/// \brief SEGMENTS.pcd writer and origin reader.

#include <pcl_ls3d/evaluation/segmentation_labels.h>
#include <pcl_ls3d/evaluation/segments_file.h>
#include <pcl_ls3d/io/pcd_io.h>

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>

namespace pcl_ls3d {
namespace evaluation {
namespace {

/// The input points back in file order: loaded points in their places, NaN where the input
/// point was not finite, segment labels and colours.
bool
fileOrderCloud(const pcl::PointCloud<pcl::PointXYZ>& cloud, const std::vector<pcl::PointIndices>& segments,
               const InputLayout& layout, pcl::PointCloud<pcl::PointXYZRGBL>& out, std::string& error)
{
  const std::size_t total = std::max(layout.points_in_file, cloud.size());
  if (cloud.size() + layout.nonfinite.size() != total) {
    error = "segments file: " + std::to_string(cloud.size()) + " loaded + " +
            std::to_string(layout.nonfinite.size()) + " non-finite points do not make the " +
            std::to_string(total) + " input points";
    return false;
  }
  const std::vector<std::uint32_t> labels = labelsFromSegments(segments, cloud.size());
  out.resize(total);
  out.is_dense = layout.nonfinite.empty();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::size_t next_bad = 0, loaded = 0;
  for (std::size_t i = 0; i < total; ++i) {
    pcl::PointXYZRGBL& p = out[i];
    if (next_bad < layout.nonfinite.size() && layout.nonfinite[next_bad] == i) {
      ++next_bad;
      p.x = p.y = p.z = nan;
      p.label = 0;
    } else {
      p.getVector3fMap() = cloud[loaded].getVector3fMap();
      p.label = labels[loaded++];
    }
    p.rgba = segmentColour(p.label);
  }
  return true;
}

/// Appends a UINT8 field "classification" to \a blob: per point the code of its label's
/// segment (label − 1), 0 for points in no segment.
void
appendClassification(const pcl::PointCloud<pcl::PointXYZRGBL>& points,
                     const std::vector<std::uint8_t>& segment_codes, pcl::PCLPointCloud2& blob)
{
  const std::size_t old_step = blob.point_step, n = points.size();
  std::vector<std::uint8_t> data(n * (old_step + 1));
  for (std::size_t i = 0; i < n; ++i) {
    std::memcpy(&data[i * (old_step + 1)], &blob.data[i * old_step], old_step);
    const std::uint32_t label = points[i].label;
    data[i * (old_step + 1) + old_step] =
        label > 0 && label <= segment_codes.size() ? segment_codes[label - 1] : 0;
  }
  pcl::PCLPointField field;
  field.name = "classification";
  field.offset = static_cast<std::uint32_t>(old_step);
  field.datatype = pcl::PCLPointField::UINT8;
  field.count = 1;
  blob.fields.push_back(field);
  blob.point_step = static_cast<std::uint32_t>(old_step + 1);
  blob.row_step = blob.point_step * blob.width;
  blob.data = std::move(data);
}

}  // namespace

bool
saveSegmentsPcd(const std::string& path, const pcl::PointCloud<pcl::PointXYZ>& cloud,
                const std::vector<pcl::PointIndices>& segments, const InputLayout& layout, std::string& error,
                const std::vector<std::uint8_t>& segment_codes)
{
  if (!segment_codes.empty() && segment_codes.size() != segments.size()) {
    error = "segments file: " + std::to_string(segment_codes.size()) + " class codes for " +
            std::to_string(segments.size()) + " segments";
    return false;
  }
  pcl::PointCloud<pcl::PointXYZRGBL> out;
  if (!fileOrderCloud(cloud, segments, layout, out, error))
    return false;
  // Packed by the writer (no padding), read by name into pcl::PointXYZRGBL.
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(out, blob);
  if (!segment_codes.empty())
    appendClassification(out, segment_codes, blob);
  // The origin line is io's, so that io::loadCloud() reads the file in the input's frame.
  std::string comments = io::kPcdSegmentsMarker + std::string("\n");
  if (!layout.crs_wkt.empty())
    comments += io::pcdCrsLine(layout.crs_wkt) + "\n";
  return io::savePcdBinaryWithOrigin(path, blob, layout.origin, comments, error);
}

namespace {

/// True when `match` accepts one of the header lines of the PCD at `path` (before DATA).
bool
anyHeaderLine(const std::string& path, const std::function<bool(const std::string&)>& match)
{
  std::ifstream f(path, std::ios::binary);
  std::string line;
  while (std::getline(f, line) && line.rfind("DATA", 0) != 0)
    if (match(line))
      return true;
  return false;
}

}  // namespace

bool
isSegmentsFile(const std::string& path)
{
  return anyHeaderLine(path, [](const std::string& line) { return io::isPcdSegmentsMarkerLine(line); });
}

bool
readSegmentsOrigin(const std::string& path, Eigen::Vector3d& origin)
{
  // The first origin line decides, as for io::loadCloud (which refuses a malformed one).
  bool found = false;
  anyHeaderLine(path, [&](const std::string& line) {
    const io::PcdOriginLine kind = io::parsePcdOriginLine(line, origin);
    found = kind == io::PcdOriginLine::Origin;
    return kind != io::PcdOriginLine::NotOrigin;
  });
  return found;
}

}  // namespace evaluation
}  // namespace pcl_ls3d
