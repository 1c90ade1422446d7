/// \file las_file.cpp
/// \brief LAS files on disk: the reader maps the file read-only (no copy of the point block), the
///        writer encodes in memory and writes once.

#include <pcl_ls3d/io/las_io.h>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

namespace pcl_ls3d {
namespace io {

bool
readLasFile(const std::string& path, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
            std::string& error, const LoadOptions& options)
{
  // Map the file read-only (no copy of the point block); fall back to one bulk read.
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) {
    error = "cannot open file";
    return false;
  }
  struct stat st;
  if (::fstat(fd, &st) != 0 || st.st_size < 0) {
    ::close(fd);
    error = "cannot determine the file size";
    return false;
  }
  const std::size_t size = static_cast<std::size_t>(st.st_size);
  if (size == 0) {
    ::close(fd);
    return readLas(nullptr, 0, cloud, info, error, options);
  }
  void* map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
  if (map != MAP_FAILED) {
    ::close(fd);
    const bool ok = readLas(static_cast<const std::uint8_t*>(map), size, cloud, info, error, options);
    ::munmap(map, size);
    return ok;
  }
  std::vector<std::uint8_t> buffer(size);
  std::size_t got = 0;
  while (got < size) {
    const ssize_t r = ::read(fd, buffer.data() + got, size - got);
    if (r <= 0)
      break;
    got += static_cast<std::size_t>(r);
  }
  ::close(fd);
  if (got != size) {
    error = "read error";
    return false;
  }
  return readLas(buffer.data(), buffer.size(), cloud, info, error, options);
}

bool
writeLasFile(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud,
             const Eigen::Vector3d& origin, std::string& error, const SaveOptions& options)
{
  std::vector<std::uint8_t> bytes;
  if (!writeLas(cloud, origin, bytes, error, options))
    return false;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out || !out.write(reinterpret_cast<const char*>(bytes.data()),
                         static_cast<std::streamsize>(bytes.size()))) {
    error = "cannot write the file";
    return false;
  }
  return true;
}

}  // namespace io
}  // namespace pcl_ls3d
