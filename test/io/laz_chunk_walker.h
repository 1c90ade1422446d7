#pragma once
/// \file laz_chunk_walker.h
/// \brief Test-side stand-in for the LAZ file reader until the container lands: reads a LAS/LAZ
///        file's header and VLRs, and decodes a LAZ file's point data by walking its chunks one
///        after the other with the bytes each occupied (the chunk table is not read). For
///        variable-sized chunks (COPC) it takes each chunk's point count from the count field
///        that layered chunks store after their first record. Swap for io::loadCloud's LAZ path
///        once that exists.

#include "io/laz/laszip_items.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace laz_test {

inline std::vector<std::uint8_t>
readFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

template <typename T>
T
get(const std::vector<std::uint8_t>& b, std::size_t at)
{
  T v{};
  if (at + sizeof(T) <= b.size())
    std::memcpy(&v, b.data() + at, sizeof(T));
  return v;
}

struct VlrRef
{
  std::string user;
  std::uint16_t record_id = 0;
  std::size_t data = 0, size = 0;  ///< payload offset and length in the file
};

/// \brief The header fields the walker needs, and the VLRs.
struct LasFile
{
  std::vector<std::uint8_t> bytes;
  int point_format = -1;  ///< without the compression bits
  bool compressed = false;
  std::size_t record_length = 0, offset_to_points = 0;
  std::uint64_t point_count = 0;
  std::vector<VlrRef> vlrs;

  const VlrRef*
  findVlr(const std::string& user, std::uint16_t id) const
  {
    for (const VlrRef& v : vlrs)
      if (v.user == user && v.record_id == id)
        return &v;
    return nullptr;
  }

  /// The uncompressed point records (valid for a LAS file only).
  std::vector<std::uint8_t>
  rawRecords() const
  {
    const std::size_t n = static_cast<std::size_t>(point_count) * record_length;
    if (offset_to_points + n > bytes.size())
      return {};
    return std::vector<std::uint8_t>(bytes.begin() + offset_to_points, bytes.begin() + offset_to_points + n);
  }
};

inline bool
openLasFile(const std::string& path, LasFile& f)
{
  f.bytes = readFile(path);
  const auto& b = f.bytes;
  if (b.size() < 227 || std::memcmp(b.data(), "LASF", 4) != 0)
    return false;
  const int minor = b[25];
  const std::uint8_t format_byte = b[104];
  f.compressed = (format_byte & 0xC0) != 0;
  f.point_format = format_byte & 0x3F;
  f.record_length = get<std::uint16_t>(b, 105);
  f.offset_to_points = get<std::uint32_t>(b, 96);
  f.point_count = get<std::uint32_t>(b, 107);
  if (minor >= 4 && b.size() >= 375)
    f.point_count = get<std::uint64_t>(b, 247);
  std::size_t at = get<std::uint16_t>(b, 94);
  const std::uint32_t vlr_count = get<std::uint32_t>(b, 100);
  for (std::uint32_t i = 0; i < vlr_count && at + 54 <= b.size(); ++i) {
    VlrRef v;
    const char* user = reinterpret_cast<const char*>(b.data() + at + 2);
    v.user.assign(user, strnlen(user, 16));
    v.record_id = get<std::uint16_t>(b, at + 18);
    v.size = get<std::uint16_t>(b, at + 20);
    v.data = at + 54;
    f.vlrs.push_back(v);
    at += 54 + v.size;
  }
  return true;
}

/// \brief The result of walking a LAZ file's chunks.
struct WalkResult
{
  bool ok = false;
  std::string error;
  pcl_ls3d::io::laz::LaszipVlr vlr;
  std::vector<std::uint8_t> records;
  std::size_t chunks = 0;
  std::size_t point_data_bytes = 0;  ///< chunk bytes walked (the chunk-table offset excluded)
  std::vector<std::size_t> chunk_bytes;
};

/// Decodes every record of a LAZ file with fixed-size chunks.
inline WalkResult
walkLaz(const LasFile& f)
{
  namespace laz = pcl_ls3d::io::laz;
  WalkResult r;
  const VlrRef* v = f.findVlr("laszip encoded", 22204);
  if (!v || v->data + v->size > f.bytes.size()) {
    r.error = "no LASzip VLR";
    return r;
  }
  if (!laz::parseLaszipVlr(f.bytes.data() + v->data, v->size, f.point_format, f.record_length, r.vlr,
                           r.error))
    return r;
  const bool variable = r.vlr.chunk_size == laz::kVariableChunkSize;
  if (variable && r.vlr.compressor != laz::Compressor::LayeredChunked) {
    r.error = "variable-sized pointwise chunks need the chunk table, which this walker does not read";
    return r;
  }
  auto decoder = laz::makeChunkDecoder(r.vlr, r.error);
  if (!decoder)
    return r;
  r.records.assign(static_cast<std::size_t>(f.point_count) * f.record_length, 0);
  const std::uint8_t* p = f.bytes.data() + f.offset_to_points + 8;  // skip the chunk-table offset
  const std::uint8_t* end = f.bytes.data() + f.bytes.size();
  for (std::uint64_t done = 0; done < f.point_count; ++r.chunks) {
    std::uint64_t n = std::min<std::uint64_t>(r.vlr.chunk_size, f.point_count - done);
    if (variable && p + f.record_length + 4 <= end) {
      std::uint32_t stored = 0;
      std::memcpy(&stored, p + f.record_length, 4);
      n = std::min<std::uint64_t>(stored, f.point_count - done);
    }
    const std::size_t used = decoder->decode(p, end, static_cast<std::size_t>(n),
                                             r.records.data() + done * f.record_length, r.error);
    if (used == 0)
      return r;
    r.chunk_bytes.push_back(used);
    r.point_data_bytes += used;
    p += used;
    done += n;
  }
  r.ok = true;
  return r;
}

}  // namespace laz_test
