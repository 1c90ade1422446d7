#pragma once
/// \file mapped_file.h
/// \brief Private: a whole file as read-only bytes, mapped (no copy) or, when mapping fails, read
///        once into memory. The binary readers (LAS, PCD, PLY) parse these bytes in place.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace detail {

class MappedFile
{
public:
  MappedFile() = default;
  MappedFile(const MappedFile&) = delete;
  MappedFile&
  operator=(const MappedFile&) = delete;
  ~MappedFile();

  /// Maps `path`; false with a one-line reason. An empty file gives size() == 0.
  bool
  open(const std::string& path, std::string& error);

  const std::uint8_t*
  data() const
  {
    return data_;
  }

  std::size_t
  size() const
  {
    return size_;
  }

private:
  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
  void* map_ = nullptr;
  std::vector<std::uint8_t> copy_;
};

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
