/// \file las_records.cpp
/// \brief Raw record access to a mapped LAS file (las_records.h).

#include <pcl_ls3d/io/las_io.h>
#include <pcl_ls3d/io/las_records.h>

#include "las_format.h"
#include "las_region.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <vector>

namespace pcl_ls3d {
namespace io {

struct LasRecordFile::Impl
{
  LasHeaderInfo header;
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  void* map = nullptr;  // mmap'ed file, or null when read into `buffer`
  std::vector<std::uint8_t> buffer;
  const std::uint8_t* records = nullptr;
  bool new_layout = false;  // point formats 6–10
  RegionInfo region;

  ~Impl()
  {
    if (map)
      ::munmap(map, size);
  }

  /// A LAZ file is decoded into memory whole, as the LAS file it compresses: records and header
  /// are then those of that LAS file (rewriteLas() writes LAS).
  bool
  decompress(std::string& error)
  {
    std::vector<std::uint8_t> las;
    if (!decompressLaz(data, size, las, error))
      return false;
    return replaceBy(las, error);
  }

  /// Only the records inside `r`, as the LAS file of their own that las::extractRegion() makes
  /// (a COPC file decodes only the nodes the box meets).
  bool
  crop(const Region& r, std::string& error)
  {
    std::vector<std::uint8_t> las;
    return las::extractRegion(data, size, header, r, las, region, error) && replaceBy(las, error);
  }

  bool
  replaceBy(std::vector<std::uint8_t>& las, std::string& error)
  {
    if (map)
      ::munmap(map, size);
    map = nullptr;
    buffer.swap(las);
    data = buffer.data();
    size = buffer.size();
    return readLasHeader(data, size, header, error);
  }
};

LasRecordFile::LasRecordFile() : impl_(std::make_unique<Impl>())
{}
LasRecordFile::~LasRecordFile() = default;
LasRecordFile::LasRecordFile(LasRecordFile&&) noexcept = default;
LasRecordFile&
LasRecordFile::operator=(LasRecordFile&&) noexcept = default;

bool
LasRecordFile::open(const std::string& path, std::string& error, const Region* region)
{
  impl_ = std::make_unique<Impl>();
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) {
    error = "cannot open " + path;
    return false;
  }
  struct stat st;
  if (::fstat(fd, &st) != 0 || st.st_size <= 0) {
    ::close(fd);
    error = path + ": empty file";
    return false;
  }
  impl_->size = static_cast<std::size_t>(st.st_size);
  void* map = ::mmap(nullptr, impl_->size, PROT_READ, MAP_PRIVATE, fd, 0);
  if (map != MAP_FAILED) {
    impl_->map = map;
    impl_->data = static_cast<const std::uint8_t*>(map);
  } else {
    impl_->buffer.resize(impl_->size);
    std::size_t got = 0;
    while (got < impl_->size) {
      const ssize_t r = ::read(fd, impl_->buffer.data() + got, impl_->size - got);
      if (r <= 0)
        break;
      got += static_cast<std::size_t>(r);
    }
    if (got != impl_->size) {
      ::close(fd);
      error = path + ": read error";
      return false;
    }
    impl_->data = impl_->buffer.data();
  }
  ::close(fd);
  if (!readLasHeader(impl_->data, impl_->size, impl_->header, error) ||
      (region && !impl_->crop(*region, error)) ||
      (impl_->header.laz.compressed && !impl_->decompress(error))) {
    error = path + ": " + error;
    return false;
  }
  impl_->records = impl_->data + impl_->header.offset_to_points;
  impl_->new_layout = impl_->header.point_format >= 6;
  return true;
}

const RegionInfo&
LasRecordFile::regionInfo() const
{
  return impl_->region;
}

const LasHeaderInfo&
LasRecordFile::header() const
{
  return impl_->header;
}

std::size_t
LasRecordFile::size() const
{
  return static_cast<std::size_t>(impl_->header.point_count);
}

const std::uint8_t*
LasRecordFile::data() const
{
  return impl_->data;
}

std::size_t
LasRecordFile::bytes() const
{
  return impl_->size;
}

const std::uint8_t*
LasRecordFile::record(std::size_t i) const
{
  return impl_->records + i * impl_->header.record_length;
}

Eigen::Vector3i
LasRecordFile::quantised(std::size_t i) const
{
  const std::uint8_t* r = record(i);
  return {las::get<std::int32_t>(r), las::get<std::int32_t>(r + 4), las::get<std::int32_t>(r + 8)};
}

Eigen::Vector3d
LasRecordFile::coordinates(std::size_t i) const
{
  const Eigen::Vector3i q = quantised(i);
  const LasHeaderInfo& h = impl_->header;
  return {q[0] * h.scale[0] + h.offset[0], q[1] * h.scale[1] + h.offset[1], q[2] * h.scale[2] + h.offset[2]};
}

std::uint8_t
LasRecordFile::classification(std::size_t i) const
{
  const std::uint8_t* r = record(i);
  return impl_->new_layout ? r[16] : static_cast<std::uint8_t>(r[15] & 0x1F);
}

LasPointFlags
LasRecordFile::flags(std::size_t i) const
{
  const std::uint8_t* r = record(i);
  LasPointFlags f;
  if (impl_->new_layout) {
    const std::uint8_t b = r[15];
    f = {(b & 1) != 0, (b & 2) != 0, (b & 4) != 0, (b & 8) != 0};
  } else {
    const std::uint8_t b = r[15];
    f = {(b & 0x20) != 0, (b & 0x40) != 0, (b & 0x80) != 0, false};
  }
  return f;
}

std::uint16_t
LasRecordFile::pointSourceId(std::size_t i) const
{
  return las::get<std::uint16_t>(record(i) + (impl_->new_layout ? 20 : 18));
}

int
LasRecordFile::returnNumber(std::size_t i) const
{
  const std::uint8_t b = record(i)[14];
  return impl_->new_layout ? (b & 0x0F) : (b & 0x07);
}

}  // namespace io
}  // namespace pcl_ls3d
