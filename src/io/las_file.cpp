/// \file las_file.cpp
/// \brief LAS files on disk: the reader maps the file read-only (no copy of the point block), the
///        writer encodes in memory and writes once.

#include <pcl_ls3d/io/las_io.h>

#include "mapped_file.h"

#include <fstream>

namespace pcl_ls3d {
namespace io {

bool
readLasFile(const std::string& path, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info, std::string& error,
            const LoadOptions& options)
{
  detail::MappedFile file;  // mapped read-only: no copy of the point block
  if (!file.open(path, error))
    return false;
  return readLas(file.data(), file.size(), cloud, info, error, options);
}

bool
writeLasFile(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
             std::string& error, const SaveOptions& options)
{
  std::vector<std::uint8_t> bytes;
  if (!writeLas(cloud, origin, bytes, error, options))
    return false;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out ||
      !out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()))) {
    error = "cannot write the file";
    return false;
  }
  return true;
}

}  // namespace io
}  // namespace pcl_ls3d
