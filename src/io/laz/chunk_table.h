#pragma once
/// \file chunk_table.h
/// \brief Private: the LASzip chunk table. It follows the chunks; the 8 bytes that start the point
///        data hold its offset (or -1, then the file's last 8 bytes do). It is a version (0), the
///        chunk count, then one arithmetic stream with per chunk its point count (only when chunks
///        vary in size) and its byte count, each coded against the previous chunk's.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace laz {

struct ChunkTable
{
  std::vector<std::uint32_t> points;  ///< per chunk (only read for variable-sized chunks)
  std::vector<std::uint64_t> bytes;   ///< per chunk
};

/// Reads the table at `offset` of the file [data, data + size). `variable`: the point counts are
/// stored. `max_chunks` bounds the count read before anything is allocated (the chunks' bytes
/// can hold no more). False with a one-line reason when the table is not there or is corrupt.
bool
readChunkTable(const std::uint8_t* data, std::size_t size, std::uint64_t offset, bool variable,
               std::uint64_t max_chunks, ChunkTable& table, std::string& error);

/// The table's bytes (version, count, coded entries); `table.points` is written when `variable`.
std::vector<std::uint8_t>
writeChunkTable(const ChunkTable& table, bool variable);

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
