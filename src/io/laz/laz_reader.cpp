/// \file laz_reader.cpp
/// \brief Reading LAZ: the records into a PointLiDAR cloud (the same fields and local frame as
///        the LAS reader, las_header.h), and the whole file back into LAS bytes.

#include <pcl_ls3d/io/las_io.h>

#include "copc_reader.h"
#include "laz_chunk_reader.h"

#include "io/las_format.h"
#include "io/las_header.h"

#include <algorithm>
#include <cstring>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl_ls3d {
namespace io {

namespace {

int
decodeThreads()
{
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

/// Until the origin is known a point keeps its record's integer X, Y, Z in the bits of its float
/// x, y, z (no arithmetic touches them before toLocalFrame), so no copy of the records is held.
void
keepIntegers(const std::uint8_t* r, PointLiDAR& p)
{
  std::memcpy(&p.x, r, 4);
  std::memcpy(&p.y, r + 4, 4);
  std::memcpy(&p.z, r + 8, 4);
}

void
toLocalFrame(pcl::PointCloud<PointLiDAR>& cloud, const las::LocalFrame& frame)
{
  const auto n = static_cast<std::ptrdiff_t>(cloud.size());
#pragma omp parallel for schedule(static) if (n > 65536)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    PointLiDAR& p = cloud[static_cast<std::size_t>(i)];
    std::int32_t q[3];
    std::memcpy(q, &p.x, 4);
    std::memcpy(q + 1, &p.y, 4);
    std::memcpy(q + 2, &p.z, 4);
    p.x = frame.local(0, q[0]);
    p.y = frame.local(1, q[1]);
    p.z = frame.local(2, q[2]);
  }
}

/// Points to reserve room for: the header's count, but no more than one per compressed byte
/// (real files take several bytes a point), so a hostile count reserves nothing large; an output
/// that needs more grows as its chunks decode.
std::size_t
reservation(const LasHeaderInfo& h, std::size_t file_size)
{
  return static_cast<std::size_t>(std::min<std::uint64_t>(h.point_count, file_size));
}

void
describe(const laz::LazChunkReader& reader, LasHeaderInfo& h)
{
  h.laz.chunk_count = reader.chunkCount();
  h.laz.chunk_table = reader.hasChunkTable();
}

}  // namespace

namespace laz_detail {

bool
describeChunks(const std::uint8_t* data, std::size_t size, LasHeaderInfo& h, std::string& error)
{
  laz::LazChunkReader reader;
  if (!reader.open(data, size, h, error))
    return false;
  describe(reader, h);
  return true;
}

bool
describeCopc(const std::uint8_t* data, std::size_t size, LasHeaderInfo& h, std::string& error)
{
  if (!laz::isCopc(h))
    return true;
  laz::CopcFile copc;
  if (!laz::openCopc(data, size, h, copc, error))
    return false;
  h.copc = laz::summariseCopc(copc);
  return true;
}

bool
readLazPoints(const std::uint8_t* data, std::size_t size, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
              std::string& error, const LoadOptions& options)
{
  LasHeaderInfo& h = info.las;
  laz::LazChunkReader reader;
  if (!reader.open(data, size, h, error))
    return false;
  describe(reader, h);
  info.points_in_file = static_cast<std::size_t>(h.point_count);
  // One integer box per chunk: chunks are visited concurrently.
  std::vector<las::IntegerBox> boxes(reader.chunkCount());
  cloud.reserve(reservation(h, size));
  const auto grow = [&](std::uint64_t points) { cloud.resize(static_cast<std::size_t>(points)); };
  const auto visit = [&](std::size_t chunk, const std::uint8_t* records, std::string&) {
    const std::size_t first = reader.firstPoint(chunk), n = reader.chunkPoints(chunk);
    las::IntegerBox& box = boxes[chunk];
    for (std::size_t j = 0; j < n; ++j) {
      const std::uint8_t* r = records + j * h.record_length;
      PointLiDAR& p = cloud[first + j];
      las::decodeAttributes(r, h, p);
      keepIntegers(r, p);
      for (int k = 0; k < 3; ++k)
        box.add(k, las::get<std::int32_t>(r + 4 * k));
    }
    return true;
  };
  if (!reader.forEachChunk(decodeThreads(), grow, visit, error))
    return false;
  las::IntegerBox box;
  for (const las::IntegerBox& b : boxes)
    for (int k = 0; k < 3; ++k) {
      box.add(k, b.lo[k]);
      box.add(k, b.hi[k]);
    }
  las::LocalFrame frame;
  if (!las::chooseFrame(box, cloud.size(), h, options, info, frame, error))
    return false;
  toLocalFrame(cloud, frame);
  info.points_loaded = cloud.size();
  return true;
}

}  // namespace laz_detail

bool
decompressLaz(const std::uint8_t* data, std::size_t size, std::vector<std::uint8_t>& out, std::string& error)
{
  out.clear();
  LasHeaderInfo h;
  if (!las::parseHeader(data, size, h, error))
    return false;
  if (!h.laz.compressed) {
    error = "the file is not compressed (LAS, not LAZ)";
    return false;
  }
  laz::LazChunkReader reader;
  if (!reader.open(data, size, h, error))
    return false;
  out = las::rebuildHead(data, h, {});
  const std::size_t head = out.size(), length = h.record_length;
  out.reserve(head + reservation(h, size) * length);
  const auto grow = [&](std::uint64_t points) { out.resize(head + points * length); };
  const auto visit = [&](std::size_t chunk, const std::uint8_t* records, std::string&) {
    std::memcpy(out.data() + head + reader.firstPoint(chunk) * length, records,
                reader.chunkPoints(chunk) * length);
    return true;
  };
  if (!reader.forEachChunk(decodeThreads(), grow, visit, error)) {
    out.clear();
    return false;
  }
  las::appendEvlrs(data, h, out);
  return true;
}

}  // namespace io
}  // namespace pcl_ls3d
