#pragma once
/// \file laz_chunk_reader.h
/// \brief Private: the LAZ container, read chunk by chunk. After the header and VLRs come (for
///        the chunked compressors) 8 bytes with the chunk table's offset, the chunks, the chunk
///        table, then any EVLRs. open() locates every chunk (from the table, or, when the table
///        is missing or unusable and the chunks have a fixed size, by decoding them in order);
///        decodeChunk() yields the records of one chunk, so a reader holds no more than the
///        chunks it is decoding beside its output. With a chunk table the chunks can be decoded in
///        any order and in parallel, one ChunkDecoder per thread.

#include <pcl_ls3d/io/cloud_io.h>

#include "laszip_items.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace laz {

/// "POINT10 v2, GPSTIME11 v2, BYTE(27) v2": the item list for people.
std::string
describeItems(const LaszipVlr& vlr);

/// A chunk of `n` points takes at least one byte for this many points (the arithmetic coder
/// cannot code a record in less than about a hundredth of a bit), so a header's claims are
/// bounded by the bytes actually present before anything is allocated for them.
constexpr std::uint64_t kMaxPointsPerByte = 4096;

class LazChunkReader
{
public:
  /// Opens the container of a file whose header `h` was parsed (las::parseHeader) from the
  /// whole file [data, data + size), which must stay valid while this reader is used.
  bool
  open(const std::uint8_t* data, std::size_t size, const LasHeaderInfo& h, std::string& error);

  const LaszipVlr&
  vlr() const
  {
    return vlr_;
  }
  std::size_t
  chunkCount() const
  {
    return points_.size();
  }
  /// Points of chunk i, and the index of its first point in the file.
  std::uint64_t
  chunkPoints(std::size_t i) const
  {
    return points_[i];
  }
  std::uint64_t
  firstPoint(std::size_t i) const
  {
    return first_[i];
  }
  /// The largest chunk's points.
  std::uint64_t
  maxChunkPoints() const
  {
    return max_points_;
  }
  /// True when the chunk table was read: chunks can then be decoded in any order, in parallel.
  bool
  hasChunkTable() const
  {
    return table_;
  }
  /// Why the table was not used (empty when it was).
  const std::string&
  tableProblem() const
  {
    return table_problem_;
  }

  /// A decoder for this file's items (one per thread).
  std::unique_ptr<ChunkDecoder>
  makeDecoder(std::string& error) const;

  /// Decodes chunk i into `out` (chunkPoints(i) · record length bytes). Without a chunk table the
  /// chunks must be decoded in order, 0, 1, 2, … (each one's end is where the next starts).
  /// With a table, calls for different chunks may run concurrently (each with its decoder).
  bool
  decodeChunk(std::size_t i, ChunkDecoder& decoder, std::uint8_t* out, std::string& error);

  /// Called with (chunk, its records): what a reader does with a decoded chunk.
  using ChunkVisitor =
      std::function<bool(std::size_t chunk, const std::uint8_t* records, std::string& error)>;

  /// Decodes every chunk and hands each to `visit`, on up to `threads` threads when there is a
  /// chunk table (visit then runs concurrently for different chunks). Before the chunks of each
  /// batch are visited, `grow` (if set) is told how many points the output must hold by then, so
  /// an output grows with the data actually decoded, not with the header's claims. Stops at the
  /// first failure; the error is that of the lowest failing chunk of its batch.
  bool
  forEachChunk(int threads, const std::function<void(std::uint64_t)>& grow, const ChunkVisitor& visit,
               std::string& error);

private:
  bool
  locateChunks(const LasHeaderInfo& h, std::string& error);
  bool
  locateTabledChunks(const LasHeaderInfo& h, std::uint64_t limit, std::string& error);
  /// The chunk table's offset, or 0 (with table_problem_) when it points nowhere usable.
  std::uint64_t
  tableOffset(const LasHeaderInfo& h, std::uint64_t limit);
  bool
  readTable(std::uint64_t table_offset, bool variable, std::string& error);
  /// Fixed-size chunks: `n` points split into chunks of `chunk_size`, the last one partial.
  bool
  splitFixed(std::uint64_t n, std::uint32_t chunk_size, std::string& error);
  /// The end of the batch of chunks that starts at `first`, decoded together by `threads`.
  std::size_t
  batchEnd(std::size_t first, std::size_t threads) const;
  /// Every chunk holds points, no more than its bytes can, and together the header's `n`.
  bool
  checkPointCounts(std::uint64_t n, std::string& error);

  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
  LaszipVlr vlr_;
  std::size_t record_length_ = 0;
  std::uint64_t chunks_begin_ = 0, chunks_end_ = 0;  // the bytes the chunks may occupy
  std::vector<std::uint64_t> points_, first_;
  std::vector<std::uint64_t> starts_;  // start of chunk i; starts_[i + 1] known once i is walked
  std::uint64_t max_points_ = 0;
  bool table_ = false;
  std::string table_problem_;
};

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
