#pragma once
/// \file record_buffer.h
/// \brief The decoded records of one LAZ chunk or COPC node (private to src/io/laz).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>

namespace pcl_ls3d {
namespace io {
namespace laz {

/// A buffer for a chunk's records, grown (never initialised: a hostile chunk that claims many
/// points but decodes few touches only the pages its decoded records fill).
struct RecordBuffer
{
  std::unique_ptr<std::uint8_t[]> bytes;
  std::size_t capacity = 0;

  /// Null when the memory cannot be had (a hostile count): the caller refuses the chunk.
  std::uint8_t*
  reserve(std::size_t n)
  {
    if (n > capacity) {
      bytes.reset(new (std::nothrow) std::uint8_t[n]);
      capacity = bytes ? n : 0;
    }
    return bytes.get();
  }
};

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
