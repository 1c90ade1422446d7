/// \file pcl_formats.cpp
/// \brief PCD/PLY via pcl::PCLPointCloud2: typed field access in double, FLOAT64 x/y/z on write.

#include "pcl_formats.h"

#include "local_origin.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
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

template <typename T>
double
as(const std::uint8_t* p)
{
  T v;
  std::memcpy(&v, p, sizeof(T));
  return static_cast<double>(v);
}

double
readAsDouble(const std::uint8_t* p, std::uint8_t datatype)
{
  switch (datatype) {
  case pcl::PCLPointField::INT8: return as<std::int8_t>(p);
  case pcl::PCLPointField::UINT8: return as<std::uint8_t>(p);
  case pcl::PCLPointField::INT16: return as<std::int16_t>(p);
  case pcl::PCLPointField::UINT16: return as<std::uint16_t>(p);
  case pcl::PCLPointField::INT32: return as<std::int32_t>(p);
  case pcl::PCLPointField::UINT32: return as<std::uint32_t>(p);
  case pcl::PCLPointField::INT64: return as<std::int64_t>(p);
  case pcl::PCLPointField::UINT64: return as<std::uint64_t>(p);
  case pcl::PCLPointField::FLOAT32: return as<float>(p);
  default: return as<double>(p);
  }
}

/// A usable field (known type, inside the point step), or nullptr.
const pcl::PCLPointField*
findField(const pcl::PCLPointCloud2& c, const std::string& name)
{
  for (const auto& f : c.fields) {
    const std::size_t size = typeSize(f.datatype);
    if (f.name == name && size > 0 && f.count >= 1 && f.offset + size <= c.point_step)
      return &f;
  }
  return nullptr;
}

/// Integer attribute clamped to [0, max]; NaN becomes 0.
template <typename T>
T
clampTo(double v)
{
  if (!(v > 0.0))
    return 0;
  const double hi = static_cast<double>(std::numeric_limits<T>::max());
  return static_cast<T>(v >= hi ? hi : std::round(v));
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

/// ASCII PLY with the same properties as the binary writer, doubles with 15 digits.
bool
writePlyAscii(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud,
              const Eigen::Vector3d& origin)
{
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f)
    return false;
  const char* xyz_type = origin.isZero(0.0) ? "float" : "double";
  bool ok = std::fprintf(f,
                         "ply\nformat ascii 1.0\ncomment pcl_ls3d\nelement vertex %zu\n"
                         "property %s x\nproperty %s y\nproperty %s z\nproperty float intensity\n"
                         "property double gps_time\nproperty ushort point_source_id\n"
                         "property uchar classification\nproperty uchar return_number\n"
                         "property uchar number_of_returns\nend_header\n",
                         cloud.size(), xyz_type, xyz_type, xyz_type) > 0;
  for (std::size_t i = 0; ok && i < cloud.size(); ++i) {
    const PointLiDAR& p = cloud[i];
    ok = std::fprintf(f, "%.15g %.15g %.15g %.9g %.15g %u %u %u %u\n", p.x + origin[0],
                      p.y + origin[1], p.z + origin[2], static_cast<double>(p.intensity),
                      p.gps_time, unsigned(p.point_source_id), unsigned(p.classification),
                      unsigned(p.return_number), unsigned(p.number_of_returns)) > 0;
  }
  return (std::fclose(f) == 0) && ok;
}

}  // namespace

bool
readPclFile(const std::string& path, const std::string& format,
            pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info, std::string& error,
            const LoadOptions& options)
{
  info = CloudInfo();
  info.format = format;
  pcl::PCLPointCloud2 c;
  int status = -1;
  bool threw = false;
  // PCL's readers print several lines on a bad file; tools promise one. Their detail stays
  // visible at debug verbosity (pcl::console::setVerbosityLevel(L_DEBUG)).
  const auto verbosity = pcl::console::getVerbosityLevel();
  if (verbosity < pcl::console::L_DEBUG)
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  try {
    status = format == "pcd" ? pcl::io::loadPCDFile(path, c) : pcl::io::loadPLYFile(path, c);
  }
  catch (const std::exception& e) {
    error = std::string("PCL's ") + format + " reader failed: " + e.what();
    threw = true;
  }
  pcl::console::setVerbosityLevel(verbosity);
  if (threw)
    return false;
  if (status < 0) {
    error = "PCL's " + format + " reader rejected the file (malformed header or truncated data)";
    return false;
  }
  const std::size_t n = static_cast<std::size_t>(c.width) * c.height;
  if (c.point_step == 0 || c.data.size() < n * c.point_step) {
    error = "point data shorter than the header says";
    return false;
  }
  const pcl::PCLPointField* fx = findField(c, "x");
  const pcl::PCLPointField* fy = findField(c, "y");
  const pcl::PCLPointField* fz = findField(c, "z");
  if (!fx || !fy || !fz) {
    error = "no x, y, z fields";
    return false;
  }
  const pcl::PCLPointField* f_int = findField(c, "intensity");
  const pcl::PCLPointField* f_time = findField(c, "gps_time");
  const pcl::PCLPointField* f_psid = findField(c, "point_source_id");
  const pcl::PCLPointField* f_class = findField(c, "classification");
  if (!f_class)
    f_class = findField(c, "label");
  const pcl::PCLPointField* f_ret = findField(c, "return_number");
  const pcl::PCLPointField* f_nret = findField(c, "number_of_returns");
  for (const pcl::PCLPointField* f : {fx, fy, fz, f_int, f_time, f_psid, f_class, f_ret, f_nret})
    if (f)
      info.fields.push_back(f->name);

  cloud.resize(n);
  std::vector<double> xyz(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* p = c.data.data() + i * c.point_step;
    xyz[3 * i] = readAsDouble(p + fx->offset, fx->datatype);
    xyz[3 * i + 1] = readAsDouble(p + fy->offset, fy->datatype);
    xyz[3 * i + 2] = readAsDouble(p + fz->offset, fz->datatype);
    PointLiDAR& q = cloud[i];
    if (f_int)
      q.intensity = static_cast<float>(readAsDouble(p + f_int->offset, f_int->datatype));
    if (f_time)
      q.gps_time = readAsDouble(p + f_time->offset, f_time->datatype);
    if (f_psid)
      q.point_source_id = clampTo<std::uint16_t>(readAsDouble(p + f_psid->offset, f_psid->datatype));
    if (f_class)
      q.classification = clampTo<std::uint8_t>(readAsDouble(p + f_class->offset, f_class->datatype));
    if (f_ret)
      q.return_number = clampTo<std::uint8_t>(readAsDouble(p + f_ret->offset, f_ret->datatype));
    if (f_nret)
      q.number_of_returns = clampTo<std::uint8_t>(readAsDouble(p + f_nret->offset, f_nret->datatype));
  }
  applyLocalOrigin(xyz, cloud, info, options);
  return true;
}

bool
writePclFile(const std::string& path, const std::string& format,
             const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
             std::string& error, const SaveOptions& options)
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
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const PointLiDAR& q = cloud[i];
    std::uint8_t* p = c.data.data() + i * c.point_step;
    std::size_t at = 0;
    for (int k = 0; k < 3; ++k) {
      const double v = static_cast<double>(q.data[k]) + origin[k];  // restore in double
      if (shifted) {
        std::memcpy(p + at, &v, 8);
        at += 8;
      }
      else {
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
  int status = -1;
  try {
    // ASCII precision 15: a UTM northing (7 digits before the point) keeps 1e-8 units.
    if (format == "pcd") {
      pcl::PCDWriter w;
      status = options.binary ? w.writeBinary(path, c)
                              : w.writeASCII(path, c, Eigen::Vector4f::Zero(),
                                             Eigen::Quaternionf::Identity(), 15);
    }
    else if (options.binary) {
      pcl::PLYWriter w;  // no camera element: other PLY readers do not expect one
      status = w.writeBinary(path, c, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity(),
                             false);
    }
    else  // PCL 1.13's ASCII PLY writer prints doubles with 6 digits: write it here
      status = writePlyAscii(path, cloud, origin) ? 0 : -1;
  }
  catch (const std::exception& e) {
    error = std::string("PCL ") + format + " writer failed: " + e.what();
    return false;
  }
  if (status < 0) {
    error = "PCL could not write the " + format + " file";
    return false;
  }
  return true;
}

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
