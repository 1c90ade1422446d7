/// \file laz_writer.cpp
/// \brief Writing LAZ: LAS bytes compressed chunk by chunk into the layout every LASzip reader
///        expects (header and VLRs with the LASzip VLR last and the point-format bit 0x80 set,
///        the 8-byte chunk table offset, the chunks, the chunk table, then the EVLRs).

#include <pcl_ls3d/io/las_io.h>

#include "chunk_table.h"
#include "laszip_items.h"

#include "io/las_format.h"
#include "io/las_header.h"

#include <cstring>
#include <fstream>

namespace pcl_ls3d {
namespace io {

namespace {

/// The LASzip VLR, header and payload.
std::vector<std::uint8_t>
laszipVlrBytes(const laz::LaszipVlr& vlr)
{
  const std::vector<std::uint8_t> payload = laz::serializeLaszipVlr(vlr);
  std::vector<std::uint8_t> bytes(las::kVlrHeaderSize + payload.size(), 0);
  std::memcpy(bytes.data() + 2, "laszip encoded", 14);
  las::put<std::uint16_t>(bytes.data() + 18, 22204);
  las::put<std::uint16_t>(bytes.data() + 20, static_cast<std::uint16_t>(payload.size()));
  const char description[] = "by pcl_ls3d (LASzip format)";
  std::memcpy(bytes.data() + 22, description, sizeof(description) - 1);
  std::memcpy(bytes.data() + las::kVlrHeaderSize, payload.data(), payload.size());
  return bytes;
}

bool
checkCompressible(const LasHeaderInfo& h, std::uint32_t chunk_size, std::string& error)
{
  if (h.laz.compressed) {
    error = "the records are compressed already (LAZ)";
    return false;
  }
  const int f = h.point_format;
  if (f == 4 || f == 5 || f == 9 || f == 10) {
    error = "point format " + std::to_string(f) +
            " carries waveform packets, which this LAZ writer does not write";
    return false;
  }
  if (chunk_size == 0 || chunk_size == laz::kVariableChunkSize) {
    error = "LAZ chunks of " + std::to_string(chunk_size) + " points are not possible";
    return false;
  }
  return true;
}

/// The records in chunks of `chunk_size`, each chunk's bytes noted for the table.
bool
appendChunks(const std::uint8_t* records, const LasHeaderInfo& h, const laz::LaszipVlr& vlr,
             std::vector<std::uint8_t>& out, laz::ChunkTable& table, std::string& error)
{
  std::unique_ptr<laz::ChunkEncoder> encoder = laz::makeChunkEncoder(vlr, error);
  if (!encoder)
    return false;
  const std::uint64_t n = h.point_count;
  for (std::uint64_t first = 0; first < n; first += vlr.chunk_size) {
    const std::uint64_t count = std::min<std::uint64_t>(vlr.chunk_size, n - first);
    const std::size_t before = out.size();
    encoder->encode(records + first * h.record_length, static_cast<std::size_t>(count), out);
    table.bytes.push_back(out.size() - before);
    if (table.bytes.back() > 0xFFFFFFFFull) {
      error = "a LAZ chunk of more than 4 GB cannot be listed in the chunk table";
      return false;
    }
  }
  return true;
}

}  // namespace

bool
compressLas(const std::uint8_t* data, std::size_t size, std::vector<std::uint8_t>& out, std::string& error,
            std::uint32_t chunk_size)
{
  out.clear();
  LasHeaderInfo h;
  if (!las::parseHeader(data, size, h, error) || !checkCompressible(h, chunk_size, error))
    return false;
  const laz::LaszipVlr vlr = laz::defaultLaszipVlr(h.point_format, h.extra_bytes_per_record, chunk_size);
  // LASzip writes its VLR after the others and marks the format byte with bit 7.
  out = las::rebuildHead(data, h, laszipVlrBytes(vlr));
  out[las::kPointFormat] |= 0x80;
  const std::size_t table_pointer = out.size();
  out.resize(out.size() + 8);
  laz::ChunkTable table;
  if (!appendChunks(data + h.offset_to_points, h, vlr, out, table, error)) {
    out.clear();
    return false;
  }
  las::put<std::int64_t>(out.data() + table_pointer, static_cast<std::int64_t>(out.size()));
  const std::vector<std::uint8_t> coded = laz::writeChunkTable(table, false);
  out.insert(out.end(), coded.begin(), coded.end());
  las::appendEvlrs(data, h, out);
  return true;
}

bool
writeLaz(const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
         std::vector<std::uint8_t>& out, std::string& error, const SaveOptions& options)
{
  std::vector<std::uint8_t> las;
  return writeLas(cloud, origin, las, error, options) && compressLas(las.data(), las.size(), out, error);
}

bool
writeLazFile(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
             std::string& error, const SaveOptions& options)
{
  std::vector<std::uint8_t> bytes;
  if (!writeLaz(cloud, origin, bytes, error, options))
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
