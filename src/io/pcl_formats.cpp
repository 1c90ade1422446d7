/// \file pcl_formats.cpp
/// \brief PCD/PLY writers via pcl::PCLPointCloud2 and PCL's writers: FLOAT64 x/y/z when the
///        origin is not zero (the readers are pcd_reader.cpp and ply_reader.cpp).

#include "pcl_formats.h"

#include "ascii_writers.h"

#include <pcl_ls3d/io/pcd_io.h>
#include <pcl_ls3d/io/ply_io.h>

#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>

namespace pcl_ls3d {
namespace io {
namespace detail {

namespace {

std::size_t
typeSize(std::uint8_t datatype)
{
  switch (datatype) {
  case pcl::PCLPointField::INT8:
  case pcl::PCLPointField::UINT8:
    return 1;
  case pcl::PCLPointField::INT16:
  case pcl::PCLPointField::UINT16:
    return 2;
  case pcl::PCLPointField::INT32:
  case pcl::PCLPointField::UINT32:
  case pcl::PCLPointField::FLOAT32:
    return 4;
  case pcl::PCLPointField::INT64:
  case pcl::PCLPointField::UINT64:
  case pcl::PCLPointField::FLOAT64:
    return 8;
  default:
    return 0;
  }
}

void
addField(pcl::PCLPointCloud2& c, const std::string& name, std::uint8_t datatype)
{
  pcl::PCLPointField f;
  f.name = name;
  f.offset = c.point_step;
  f.datatype = datatype;
  f.count = 1;
  c.fields.push_back(f);
  c.point_step += static_cast<std::uint32_t>(typeSize(datatype));
}

// One point's fields in the blob's layout: x/y/z in double (restored with the origin) when
// shifted, else in float.
void
packPoint(const PointLiDAR& q, const Eigen::Vector3d& origin, bool shifted, std::uint8_t* p)
{
  std::size_t at = 0;
  for (int k = 0; k < 3; ++k) {
    const double v = static_cast<double>(q.data[k]) + origin[k];  // restore in double
    if (shifted) {
      std::memcpy(p + at, &v, 8);
      at += 8;
    } else {
      const float f = q.data[k];
      std::memcpy(p + at, &f, 4);
      at += 4;
    }
  }
  std::memcpy(p + at, &q.intensity, 4);
  std::memcpy(p + at + 4, &q.gps_time, 8);
  std::memcpy(p + at + 12, &q.point_source_id, 2);
  p[at + 14] = q.classification;
  p[at + 15] = q.return_number;
  p[at + 16] = q.number_of_returns;
}

// The cloud as a PCLPointCloud2 blob for PCL's binary writers.
pcl::PCLPointCloud2
lidarBlob(const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin)
{
  const bool shifted = !origin.isZero(0.0);
  const std::uint8_t xyz_type = shifted ? pcl::PCLPointField::FLOAT64 : pcl::PCLPointField::FLOAT32;
  pcl::PCLPointCloud2 c;
  c.point_step = 0;
  for (const char* name : {"x", "y", "z"})
    addField(c, name, xyz_type);
  addField(c, "intensity", pcl::PCLPointField::FLOAT32);
  addField(c, "gps_time", pcl::PCLPointField::FLOAT64);
  addField(c, "point_source_id", pcl::PCLPointField::UINT16);
  addField(c, "classification", pcl::PCLPointField::UINT8);
  addField(c, "return_number", pcl::PCLPointField::UINT8);
  addField(c, "number_of_returns", pcl::PCLPointField::UINT8);
  c.width = static_cast<std::uint32_t>(cloud.size());
  c.height = 1;
  c.is_dense = cloud.is_dense;
  c.row_step = c.point_step * c.width;
  c.data.resize(static_cast<std::size_t>(c.row_step));
  for (std::size_t i = 0; i < cloud.size(); ++i)
    packPoint(cloud[i], origin, shifted, c.data.data() + i * c.point_step);
  return c;
}

// Writes the file in the format; PCL's status (< 0: failed). May throw from PCL's writers.
int
writeFormat(const std::string& path, const std::string& format, const pcl::PointCloud<PointLiDAR>& cloud,
            const Eigen::Vector3d& origin, const pcl::PCLPointCloud2& c, const SaveOptions& options)
{
  // ASCII: pcl_ls3d's own writers (ascii_writers.h) print every number exactly; PCL 1.13's
  // print a fixed number of digits (PLY doubles: 6).
  const bool crs = !options.crs_wkt.empty();
  const std::string comments =
      !crs ? "" : (format == "pcd" ? pcdCrsLine(options.crs_wkt) : plyCrsLine(options.crs_wkt)) + "\n";
  if (!options.binary)
    return (format == "pcd" ? writePcdAscii(path, cloud, origin, comments)
                            : writePlyAscii(path, cloud, origin, comments))
               ? 0
               : -1;
  if (format == "pcd") {
    std::string why;  // names the path, which saveCloud() adds itself
    return savePcdBinaryWithComments(path, c, comments, why) ? 0 : -1;
  }
  // No camera element: other PLY readers do not expect one.
  int status =
      pcl::PLYWriter().writeBinary(path, c, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity(), false);
  if (status >= 0 && !insertPlyComments(path, comments))
    status = -1;
  return status;
}

}  // namespace

bool
writePclFile(const std::string& path, const std::string& format, const pcl::PointCloud<PointLiDAR>& cloud,
             const Eigen::Vector3d& origin, std::string& error, const SaveOptions& options)
{
  const pcl::PCLPointCloud2 c = lidarBlob(cloud, origin);
  int status = -1;
  try {
    status = writeFormat(path, format, cloud, origin, c, options);
  } catch (const std::exception& e) {
    error = std::string("PCL ") + format + " writer failed: " + e.what();
    return false;
  }
  if (status < 0) {
    error = "could not write the " + format + " file";
    return false;
  }
  return true;
}

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
