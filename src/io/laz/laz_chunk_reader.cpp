/// \file laz_chunk_reader.cpp
/// \brief The LAZ container: locating the chunks (from the chunk table or by walking them) and
///        decoding them, in parallel when the table allows (laz_chunk_reader.h).

#include "laz_chunk_reader.h"
#include "record_buffer.h"

#include "chunk_table.h"

#include "io/las_format.h"

#include <algorithm>
#include <new>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

const char*
itemName(ItemType type)
{
  switch (type) {
  case ItemType::Byte:
    return "BYTE";
  case ItemType::Point10:
    return "POINT10";
  case ItemType::GpsTime11:
    return "GPSTIME11";
  case ItemType::Rgb12:
    return "RGB12";
  case ItemType::Wavepacket13:
    return "WAVEPACKET13";
  case ItemType::Point14:
    return "POINT14";
  case ItemType::Rgb14:
    return "RGB14";
  case ItemType::RgbNir14:
    return "RGBNIR14";
  case ItemType::Wavepacket14:
    return "WAVEPACKET14";
  case ItemType::Byte14:
    return "BYTE14";
  default:
    return "ITEM";
  }
}

/// Where the EVLRs start (the compressed data ends before them), or `size` when there are none.
std::uint64_t
evlrStart(const std::uint8_t* data, std::size_t size, const LasHeaderInfo& h)
{
  if (h.version_minor < 4 || h.evlrs.empty())
    return size;
  return std::min<std::uint64_t>(las::get<std::uint64_t>(data + las::kEvlrStart), size);
}

}  // namespace

std::string
describeItems(const LaszipVlr& vlr)
{
  std::ostringstream s;
  for (std::size_t i = 0; i < vlr.items.size(); ++i) {
    const Item& item = vlr.items[i];
    s << (i ? ", " : "") << itemName(item.type);
    if (item.type == ItemType::Byte || item.type == ItemType::Byte14)
      s << "(" << item.size << ")";
    s << " v" << item.version;
  }
  return s.str();
}

bool
LazChunkReader::open(const std::uint8_t* data, std::size_t size, const LasHeaderInfo& h, std::string& error)
{
  *this = LazChunkReader();
  data_ = data;
  size_ = size;
  record_length_ = h.record_length;
  const LasVlr* found = nullptr;
  for (const LasVlr& v : h.vlrs)
    if (v.user_id == "laszip encoded" && v.record_id == 22204)
      found = &v;
  if (!found) {
    error = "the file has no LASzip VLR";
    return false;
  }
  return parseLaszipVlr(found->data.data(), found->data.size(), h.point_format, h.record_length, vlr_,
                        error) &&
         locateChunks(h, error);
}

bool
LazChunkReader::splitFixed(std::uint64_t n, std::uint32_t chunk_size, std::string& error)
{
  const std::uint64_t chunks = n / chunk_size + (n % chunk_size != 0);
  const std::uint64_t room = (chunks_end_ - chunks_begin_) / (record_length_ + 4);
  if (chunks > room) {
    error = "the header's " + std::to_string(n) + " points in chunks of " + std::to_string(chunk_size) +
            " make " + std::to_string(chunks) + " chunks, more than the " +
            std::to_string(chunks_end_ - chunks_begin_) + " bytes of compressed data can hold";
    return false;
  }
  points_.assign(chunks, chunk_size);
  if (chunks > 0 && n % chunk_size != 0)
    points_.back() = n % chunk_size;
  return true;
}

bool
LazChunkReader::readTable(std::uint64_t table_offset, bool variable, std::string& error)
{
  const std::uint64_t area = table_offset - chunks_begin_;
  ChunkTable table;
  if (!readChunkTable(data_, size_, table_offset, variable, area / (record_length_ + 4), table, error))
    return false;
  std::uint64_t pos = chunks_begin_;
  for (std::size_t i = 0; i < table.bytes.size(); ++i) {
    if (table.bytes[i] == 0 || table.bytes[i] > table_offset - pos) {
      error = "the chunk table's chunk " + std::to_string(i) + " of " + std::to_string(table.bytes[i]) +
              " bytes at byte " + std::to_string(pos) + " does not end before the table at byte " +
              std::to_string(table_offset);
      return false;
    }
    starts_.push_back(pos);
    pos += table.bytes[i];
  }
  starts_.push_back(pos);
  if (variable)
    points_.assign(table.points.begin(), table.points.end());
  chunks_end_ = table_offset;
  return true;
}

std::uint64_t
LazChunkReader::tableOffset(const LasHeaderInfo& h, std::uint64_t limit)
{
  auto offset = las::get<std::int64_t>(data_ + h.offset_to_points);
  if (offset == -1 && size_ >= 8)  // written to a stream: the offset ends the file
    offset = las::get<std::int64_t>(data_ + size_ - 8);
  if (offset == static_cast<std::int64_t>(h.offset_to_points)) {
    table_problem_ = "the writer stopped before writing the chunk table";
    return 0;
  }
  if (offset < static_cast<std::int64_t>(chunks_begin_) || static_cast<std::uint64_t>(offset) > limit) {
    table_problem_ = "the chunk table offset " + std::to_string(offset) + " lies outside the compressed data";
    return 0;
  }
  return static_cast<std::uint64_t>(offset);
}

bool
LazChunkReader::locateTabledChunks(const LasHeaderInfo& h, std::uint64_t limit, std::string& error)
{
  if (limit - h.offset_to_points < 8) {
    error = "the LAZ point data is truncated: not even the 8-byte chunk table offset is there";
    return false;
  }
  chunks_begin_ = h.offset_to_points + 8;
  chunks_end_ = limit;
  const bool variable = vlr_.chunk_size == kVariableChunkSize;
  if (!variable && !splitFixed(h.point_count, vlr_.chunk_size, error))
    return false;
  if (const std::uint64_t offset = tableOffset(h, limit)) {
    chunks_end_ = offset;
    table_ = readTable(offset, variable, table_problem_);
    if (table_ && !variable && starts_.size() - 1 != points_.size()) {
      table_problem_ = "the chunk table lists " + std::to_string(starts_.size() - 1) +
                       " chunks, the header's " + std::to_string(h.point_count) + " points need " +
                       std::to_string(points_.size());
      table_ = false;
    }
  }
  if (table_)
    return true;
  if (variable) {
    error = table_problem_ + " (chunks of varying size cannot be found without it)";
    return false;
  }
  starts_.assign(1, chunks_begin_);  // the rest are found by decoding the chunks in order
  return true;
}

bool
LazChunkReader::checkPointCounts(std::uint64_t n, std::string& error)
{
  std::uint64_t total = 0;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const std::uint64_t bytes = table_ ? starts_[i + 1] - starts_[i] : chunks_end_ - chunks_begin_;
    if (points_[i] == 0 || points_[i] > kMaxPointsPerByte * bytes) {
      error = "chunk " + std::to_string(i) + " claims " + std::to_string(points_[i]) + " points in " +
              std::to_string(bytes) + " bytes";
      return false;
    }
    first_.push_back(total);
    total += points_[i];
    max_points_ = std::max(max_points_, points_[i]);
  }
  if (total != n) {
    error = "the chunks hold " + std::to_string(total) + " points, the header says " + std::to_string(n);
    return false;
  }
  return true;
}

bool
LazChunkReader::locateChunks(const LasHeaderInfo& h, std::string& error)
{
  const std::uint64_t limit = std::max<std::uint64_t>(evlrStart(data_, size_, h), h.offset_to_points);
  if (vlr_.compressor == Compressor::Pointwise) {
    // One stream for all points, straight after the VLRs, and no chunk table.
    chunks_begin_ = h.offset_to_points;
    chunks_end_ = limit;
    if (h.point_count > 0)
      points_.assign(1, h.point_count);
    starts_.assign(1, chunks_begin_);
  } else if (!locateTabledChunks(h, limit, error)) {
    return false;
  }
  return checkPointCounts(h.point_count, error);
}

std::unique_ptr<ChunkDecoder>
LazChunkReader::makeDecoder(std::string& error) const
{
  return makeChunkDecoder(vlr_, error);
}

bool
LazChunkReader::decodeChunk(std::size_t i, ChunkDecoder& decoder, std::uint8_t* out, std::string& error)
{
  const std::string where = "chunk " + std::to_string(i + 1) + " of " + std::to_string(chunkCount());
  if (i >= starts_.size()) {
    error = where + " cannot be found before the chunks ahead of it are decoded (no chunk table)";
    return false;
  }
  const std::uint64_t begin = starts_[i];
  const std::uint64_t end = table_ ? starts_[i + 1] : chunks_end_;
  const std::size_t used =
      decoder.decode(data_ + begin, data_ + end, static_cast<std::size_t>(points_[i]), out, error);
  if (used == 0) {
    error = where + ": " + error;
    return false;
  }
  if (table_ && used != end - begin) {
    error = where + ": its points take " + std::to_string(used) + " bytes, the chunk table says " +
            std::to_string(end - begin) + " (corrupt chunk or table)";
    return false;
  }
  if (!table_ && i + 1 == starts_.size())
    starts_.push_back(begin + used);
  return true;
}

namespace {

// Points a thread should have to decode before a second one is worth waking: below, a parallel
// region costs more than it saves (and a forked child, which a parent's OpenMP pool does not
// survive, stays serial on small files).
constexpr std::uint64_t kPointsPerThread = 65536;

}  // namespace

std::size_t
LazChunkReader::batchEnd(std::size_t first, std::size_t threads) const
{
  // At least one chunk per thread, and some chunks' worth of points per thread, so that the
  // waits at the end of a batch's two parallel regions cost little beside the decoding (small
  // chunks come in the hundreds); the batch's records are what is held beside the output.
  constexpr std::size_t kMaxChunks = 4096;
  constexpr std::uint64_t kBatchPointsPerThread = 4 * kPointsPerThread;
  std::size_t end = first;
  std::uint64_t points = 0;
  while (end < chunkCount() && end - first < kMaxChunks &&
         (end - first < threads || points < threads * kBatchPointsPerThread))
    points += points_[end++];
  return end;
}

bool
LazChunkReader::forEachChunk(int threads, const std::function<void(std::uint64_t)>& grow,
                             const ChunkVisitor& visit, std::string& error)
{
  // Batches of chunks: decoded in parallel, then the output grown once (serially) to hold them,
  // then visited in parallel. Memory: the output so far plus one batch of decoded chunks.
  const std::size_t workers = table_ ? static_cast<std::size_t>(std::max(1, threads)) : 1;
  std::vector<std::unique_ptr<ChunkDecoder>> decoders(workers);
  for (auto& d : decoders)
    if (!(d = makeDecoder(error)))
      return false;
  std::vector<RecordBuffer> buffers;
  std::vector<std::string> errors;
  std::vector<char> ok;
  const auto firstFailure = [&](std::size_t m) {
    for (std::size_t t = 0; t < m; ++t)
      if (!ok[t]) {
        error = errors[t];
        return true;
      }
    return false;
  };
  for (std::size_t b = 0; b < chunkCount();) {
    const std::size_t e = table_ ? batchEnd(b, workers) : b + 1, m = e - b;
    buffers.resize(std::max(buffers.size(), m));
    errors.assign(m, std::string());
    ok.assign(m, 0);
    const std::uint64_t points = first_[e - 1] + points_[e - 1] - first_[b];
    const int team = points < kPointsPerThread ? 1 : static_cast<int>(std::min(m, workers));
#pragma omp parallel for num_threads(team) schedule(dynamic, 1) if (team > 1)
    for (std::size_t t = 0; t < m; ++t) {
      std::size_t worker = 0;
#ifdef _OPENMP
      worker = static_cast<std::size_t>(omp_get_thread_num());
#endif
      const std::size_t bytes = static_cast<std::size_t>(points_[b + t]) * record_length_;
      std::uint8_t* out = buffers[t].reserve(bytes);
      ok[t] = out ? decodeChunk(b + t, *decoders[worker], out, errors[t])
                  : (errors[t] = "chunk " + std::to_string(b + t + 1) + ": no memory for the " +
                                 std::to_string(bytes) + " bytes of its " + std::to_string(points_[b + t]) +
                                 " points",
                     false);
    }
    if (firstFailure(m))
      return false;
    if (grow)
      grow(first_[e - 1] + points_[e - 1]);
#pragma omp parallel for num_threads(team) schedule(dynamic, 1) if (team > 1)
    for (std::size_t t = 0; t < m; ++t)
      ok[t] = visit(b + t, buffers[t].bytes.get(), errors[t]);
    if (firstFailure(m))
      return false;
    b = e;
  }
  return true;
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
