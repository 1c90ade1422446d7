/// \file las_rewrite.cpp
/// \brief Record-by-record LAS rewrite with corrected coordinates (las_rewrite.h).

#include <pcl_ls3d/io/las_io.h>
#include <pcl_ls3d/io/las_rewrite.h>

#include "las_format.h"
#include "las_header.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sys/stat.h>

namespace pcl_ls3d {
namespace io {

namespace {

bool
exists(const std::string& path)
{
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

// Quantises file coordinates with the header's scale and offset; false outside int32.
bool
quantise(const Eigen::Vector3d& x, const LasHeaderInfo& h, std::int32_t q[3])
{
  for (int k = 0; k < 3; ++k) {
    const double v = std::round((x[k] - h.offset[k]) / h.scale[k]);
    if (!(v >= std::numeric_limits<std::int32_t>::min() && v <= std::numeric_limits<std::int32_t>::max()))
      return false;
    q[k] = static_cast<std::int32_t>(v);
  }
  return true;
}

// Offsets of data after the records (1.3 waveform packets, 1.4 EVLRs) move with the record block.
void
shiftTailOffsets(std::vector<std::uint8_t>& head, const LasHeaderInfo& h, std::uint64_t old_end,
                 std::int64_t delta)
{
  auto shift = [&](std::size_t at) {
    if (head.size() < at + 8)
      return;
    const std::uint64_t v = las::get<std::uint64_t>(head.data() + at);
    if (v >= old_end)
      las::put<std::uint64_t>(head.data() + at,
                              static_cast<std::uint64_t>(static_cast<std::int64_t>(v) + delta));
  };
  if (h.version_minor >= 3)
    shift(las::kWaveformStart);
  if (h.version_minor >= 4)
    shift(las::kEvlrStart);
}

// The rewritten records with their integer bounds and counts per return number.
struct RecordBlock
{
  std::vector<std::uint8_t> records;
  las::IntegerBox box;
  std::uint64_t by_return[15] = {};
};

// Copies record i to `out`, with its coordinates moved and quantised when `move` moves them.
bool
copyRecord(const LasRecordFile& in, std::size_t i, const RecordMover& move, const std::string& path,
           std::uint8_t* out, LasRewriteSummary& summary, std::string& error)
{
  const std::size_t stride = in.header().record_length;
  std::copy(in.record(i), in.record(i) + stride, out);
  Eigen::Vector3d x = in.coordinates(i);
  if (move && move(i, x)) {
    std::int32_t q[3];
    if (!quantise(x, in.header(), q)) {
      error = "a corrected coordinate does not fit the scale and offset of " + path;
      return false;
    }
    for (int c = 0; c < 3; ++c)
      las::put<std::int32_t>(out + 4 * c, q[c]);
    ++summary.moved;
  }
  return true;
}

// The n selected records (all when `selection` is null), moved, with their bounds and counts.
bool
copyRecords(const LasRecordFile& in, const std::vector<std::size_t>* selection, std::size_t n,
            const RecordMover& move, const std::string& path, RecordBlock& block, LasRewriteSummary& summary,
            std::string& error)
{
  const std::size_t stride = in.header().record_length;
  block.records.resize(n * stride);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = selection ? (*selection)[k] : k;
    if (i >= in.size()) {
      error = "record index out of range";
      return false;
    }
    std::uint8_t* out = block.records.data() + k * stride;
    if (!copyRecord(in, i, move, path, out, summary, error))
      return false;
    for (int c = 0; c < 3; ++c) {
      block.box.add(c, las::get<std::int32_t>(out + 4 * c));
    }
    const int ret = in.returnNumber(i);
    if (ret >= 1 && ret <= 15)
      ++block.by_return[ret - 1];
  }
  return true;
}

// The whole file: header and VLRs (and any bytes before the records) as they are with the
// changed fields, the records, then the bytes after the old records.
std::vector<std::uint8_t>
assembleFile(const LasRecordFile& in, bool selected, std::size_t n, RecordBlock& block)
{
  const LasHeaderInfo& h = in.header();
  const std::size_t stride = h.record_length;
  const std::uint64_t old_end = h.offset_to_points + static_cast<std::uint64_t>(in.size()) * stride;
  std::vector<std::uint8_t> head(in.data(), in.data() + h.offset_to_points);
  las::writeBounds(head, h, block.box, n == 0);
  if (selected) {
    las::writeCounts(head, h, n, block.by_return);
    shiftTailOffsets(head, h, old_end,
                     static_cast<std::int64_t>(n * stride) - static_cast<std::int64_t>(in.size() * stride));
  }
  const std::uint8_t* tail = in.data() + std::min<std::uint64_t>(old_end, in.bytes());
  const std::size_t tail_size = in.bytes() > old_end ? static_cast<std::size_t>(in.bytes() - old_end) : 0;
  std::vector<std::uint8_t> bytes = std::move(head);
  bytes.insert(bytes.end(), block.records.begin(), block.records.end());
  block.records = std::vector<std::uint8_t>();
  bytes.insert(bytes.end(), tail, tail + tail_size);
  return bytes;
}

// Writes the file, compressed when the name asks for LAZ.
bool
writeBytes(const std::string& path, std::vector<std::uint8_t>& bytes, std::string& error)
{
  if (fileExtension(path) == "laz") {  // the name asks for LAZ: the same file, compressed
    std::vector<std::uint8_t> laz;
    if (!compressLas(bytes.data(), bytes.size(), laz, error)) {
      error = "cannot write " + path + " as LAZ: " + error;
      return false;
    }
    bytes.swap(laz);
  }
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file ||
      !file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())) ||
      !file.flush()) {
    error = "cannot write " + path;
    return false;
  }
  return true;
}

}  // namespace

bool
rewriteLas(const LasRecordFile& in, const std::vector<std::size_t>* selection, const RecordMover& move,
           const std::string& path, LasRewriteSummary& summary, std::string& error, bool overwrite)
{
  summary = LasRewriteSummary();
  if (!overwrite && exists(path)) {
    error = path + " exists (not overwritten)";
    return false;
  }
  const std::size_t n = selection ? selection->size() : in.size();
  RecordBlock block;
  if (!copyRecords(in, selection, n, move, path, block, summary, error))
    return false;
  std::vector<std::uint8_t> bytes = assembleFile(in, selection != nullptr, n, block);
  if (!writeBytes(path, bytes, error))
    return false;
  summary.points = n;
  return true;
}

}  // namespace io
}  // namespace pcl_ls3d
