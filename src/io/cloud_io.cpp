/// \file cloud_io.cpp
/// \brief loadCloud()/saveCloud(): format detection, overwrite protection and the local origin.

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/las_io.h>
#include <pcl_ls3d/io/pcd_io.h>
#include <pcl_ls3d/io/ply_io.h>
#include <pcl_ls3d/io/xyz_io.h>

#include "las_region.h"
#include "mapped_file.h"
#include "pcl_formats.h"
#include "point_fields.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

namespace pcl_ls3d {
namespace io {

namespace fs = std::filesystem;

std::string
fileExtension(const std::string& path)
{
  std::string ext = fs::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.')
    ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool
isSameFile(const std::string& a, const std::string& b)
{
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool same = fs::equivalent(a, b, ec);
    if (!ec)
      return same;
  }
  // At least one does not exist yet: compare the normalised absolute paths.
  const fs::path pa = fs::weakly_canonical(fs::absolute(a, ec), ec);
  const fs::path pb = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return pa == pb;
}

namespace {

/// "las", "laz", "pcd", "ply", "xyz" from the first bytes, else "".
std::string
sniffFormat(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  char head[16] = {};
  in.read(head, sizeof(head));
  const std::streamsize got = in.gcount();
  const std::string s(head, static_cast<std::size_t>(got));
  if (s.compare(0, 4, "LASF") == 0)
    return "las";
  if (s.compare(0, 4, "ply\n") == 0 || s.compare(0, 4, "ply\r") == 0)
    return "ply";
  if (s.compare(0, 6, "# .PCD") == 0 || s.compare(0, 7, "VERSION") == 0 || s.compare(0, 6, "FIELDS") == 0)
    return "pcd";
  return "";
}

std::string
formatOf(const std::string& ext)
{
  if (ext == "las" || ext == "pcd" || ext == "ply" || ext == "laz")
    return ext;
  if (ext == "xyz" || ext == "txt" || ext == "csv" || ext == "asc" || ext == "pts")
    return "xyz";
  return "";
}

/// A region on a file without an octree or records (PCD, PLY, XYZ): the points are read, then
/// those outside the box are left out; the local origin stays the one of the whole file.
void
keepRegion(const Region& region, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info)
{
  const int dims = region.use_z ? 3 : 2;
  std::size_t kept = 0;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const PointLiDAR& p : cloud.points) {
    const Eigen::Vector3d x = info.origin + p.getVector3fMap().cast<double>();
    if (((x.head(dims).array() >= region.box.min().head(dims).array()) &&
         (x.head(dims).array() <= region.box.max().head(dims).array()))
            .all()) {
      cloud.points[kept++] = p;
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
  }
  info.region.applied = true;
  info.region.points_decoded = cloud.size();
  info.points_outside_region = cloud.size() - kept;
  cloud.points.resize(kept);
  cloud.width = static_cast<std::uint32_t>(kept);
  cloud.height = 1;
  info.points_loaded = kept;
  info.min_file = kept ? lo : Eigen::Vector3d::Zero();
  info.max_file = kept ? hi : Eigen::Vector3d::Zero();
}

bool
loadByFormat(const std::string& format, const std::string& path, pcl::PointCloud<PointLiDAR>& cloud,
             CloudInfo& info, std::string& error, const LoadOptions& options)
{
  if (format == "las" || format == "laz")  // a LAZ file is LAS with compressed records
    return readLasFile(path, cloud, info, error, options);
  LoadOptions whole = options;  // the region is applied below, once the points are read
  whole.region.reset();
  if (options.region) {
    if (options.region->max_level >= 0) {
      error = "a maximum octree level needs a COPC file (.copc.laz); this one has no octree";
      return false;
    }
    whole.allow_empty = true;
  }
  bool ok = false;
  if (format == "pcd" || format == "ply") {
    detail::MappedFile file;
    if (!file.open(path, error))
      return false;
    ok = format == "pcd" ? readPcd(file.data(), file.size(), cloud, info, error, whole)
                         : readPly(file.data(), file.size(), cloud, info, error, whole);
  } else {
    std::ifstream in(path);
    if (!in) {
      error = "cannot open file";
      return false;
    }
    ok = readXyz(in, cloud, info, error, whole);
  }
  if (ok && options.region)
    keepRegion(*options.region, cloud, info);
  return ok;
}

}  // namespace

bool
loadCloud(const std::string& path, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info, std::string& error,
          const LoadOptions& options)
{
  cloud.clear();
  info = CloudInfo();
  std::string reason;
  std::error_code ec;
  const std::string ext = fileExtension(path);
  std::string format;
  if (!fs::exists(path, ec))
    reason = "file does not exist";
  else if (fs::is_directory(path, ec))
    reason = "is a directory, not a point-cloud file";
  else if (fs::file_size(path, ec) == 0)
    reason = "empty file";
  else {
    format = sniffFormat(path);
    if (format.empty())
      format = formatOf(ext);
    if (format.empty())
      reason = "unknown file type " + detail::quote("." + ext) +
               " (supported: .las .laz .pcd .ply .xyz .txt .csv)";
  }
  if (reason.empty() && !options.origin.allFinite() && options.use_origin)
    reason = "the forced origin is not finite";
  if (reason.empty() && options.region)
    las::checkRegion(*options.region, reason);
  if (reason.empty() && !loadByFormat(format, path, cloud, info, reason, options))
    cloud.clear();
  else if (reason.empty() && info.points_loaded == 0 && !options.allow_empty) {
    reason = info.points_outside_region > 0 ? std::string("no point of the file lies inside the region")
             : info.points_in_file == 0
                 ? std::string("no points in the file")
                 : "no finite points (all " + std::to_string(info.points_in_file) + " points are NaN/inf)";
  }
  if (!reason.empty()) {
    error = detail::printable(path) + ": " + reason;
    return false;
  }
  return true;
}

bool
canSaveFormat(const std::string& path, std::string& why)
{
  const std::string ext = fileExtension(path);
  const std::string format = formatOf(ext);
  if (!format.empty())
    return true;
  why = "cannot write " + detail::quote("." + ext) + " files (supported: .las .laz .pcd .ply .xyz .txt .csv)";
  return false;
}

bool
saveCloud(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
          std::string& error, const SaveOptions& options)
{
  const std::string format = formatOf(fileExtension(path));
  std::string reason;
  std::error_code ec;
  if (!canSaveFormat(path, reason)) {
    error = detail::printable(path) + ": " + reason;
    return false;
  }
  if (cloud.empty())
    reason = "refusing to write an empty cloud";
  else if (!origin.allFinite())
    reason = "the origin is not finite";
  else if (fs::exists(path, ec) && !options.overwrite)
    reason = "exists already (use -overwrite to replace it)";
  else if (fs::is_directory(path, ec))
    reason = "is a directory";
  else if (format == "las")
    writeLasFile(path, cloud, origin, reason, options);
  else if (format == "laz")
    writeLazFile(path, cloud, origin, reason, options);
  else if (format == "xyz")
    writeXyzFile(path, cloud, origin, reason, options);
  else
    detail::writePclFile(path, format, cloud, origin, reason, options);
  if (!reason.empty()) {
    error = detail::printable(path) + ": " + reason;
    return false;
  }
  return true;
}

}  // namespace io
}  // namespace pcl_ls3d
