/// \file mapped_file.cpp
/// \brief Read-only file bytes by mmap, or one bulk read when mapping fails.

#include "mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pcl_ls3d {
namespace io {
namespace detail {

MappedFile::~MappedFile()
{
  if (map_)
    ::munmap(map_, size_);
}

bool
MappedFile::open(const std::string& path, std::string& error)
{
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
  size_ = static_cast<std::size_t>(st.st_size);
  if (size_ == 0) {
    ::close(fd);
    return true;
  }
  void* map = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
  if (map != MAP_FAILED) {
    ::close(fd);
    map_ = map;
    data_ = static_cast<const std::uint8_t*>(map);
    return true;
  }
  copy_.resize(size_);
  std::size_t got = 0;
  while (got < size_) {
    const ssize_t r = ::read(fd, copy_.data() + got, size_ - got);
    if (r <= 0)
      break;
    got += static_cast<std::size_t>(r);
  }
  ::close(fd);
  if (got != size_) {
    error = "read error";
    return false;
  }
  data_ = copy_.data();
  return true;
}

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
