#pragma once
/// \file laszip_items.h
/// \brief Private: the LASzip VLR (user "laszip encoded", record 22204) and the item list it
///        declares, parsed and validated, plus the chunk codec interface that the pointwise
///        (formats 0–5) and layered (formats 6–10) item coders implement.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace laz {

/// LASzip item types (the values are the format's).
enum class ItemType : std::uint16_t
{
  Byte = 0,
  Short = 1,
  Integer = 2,
  Long = 3,
  Float = 4,
  Double = 5,
  Point10 = 6,
  GpsTime11 = 7,
  Rgb12 = 8,
  Wavepacket13 = 9,
  Point14 = 10,
  Rgb14 = 11,
  RgbNir14 = 12,
  Wavepacket14 = 13,
  Byte14 = 14,
};

/// Compressor field of the VLR.
enum class Compressor : std::uint16_t
{
  None = 0,
  Pointwise = 1,         ///< one arithmetic stream for all points (old files)
  PointwiseChunked = 2,  ///< formats 0–5 in chunks, with a chunk table
  LayeredChunked = 3,    ///< formats 6–10 in chunks of per-field layers, with a chunk table
};

struct Item
{
  ItemType type = ItemType::Byte;
  std::uint16_t size = 0;     ///< bytes of the record this item covers
  std::uint16_t version = 0;  ///< coder version (1, 2, 3 or 4)
};

/// Chunk size of a file with variable-sized chunks (the chunk table then holds the counts).
constexpr std::uint32_t kVariableChunkSize = 0xFFFFFFFFu;

/// \brief The content of the LASzip VLR.
struct LaszipVlr
{
  Compressor compressor = Compressor::None;
  std::uint16_t coder = 0;  ///< 0: arithmetic (the only one defined)
  std::uint8_t version_major = 0, version_minor = 0;
  std::uint16_t version_revision = 0;
  std::uint32_t options = 0;
  std::uint32_t chunk_size = 0;  ///< points per chunk, or kVariableChunkSize
  std::int64_t special_evlr_count = -1, special_evlr_offset = -1;
  std::vector<Item> items;

  /// Bytes of one point record the items cover (must equal the header's record length).
  std::size_t
  recordLength() const;
};

/// Parses and checks a LASzip VLR payload against the header's point format and record length
/// (known compressor, coder 0, item types and versions this decoder implements, item sizes that
/// add up to the record). False with a one-line reason naming what is wrong.
bool
parseLaszipVlr(const std::uint8_t* data, std::size_t size, int point_format, std::size_t record_length,
               LaszipVlr& vlr, std::string& error);

/// The VLR payload for `vlr` (34 + 6 · items bytes).
std::vector<std::uint8_t>
serializeLaszipVlr(const LaszipVlr& vlr);

/// The item list pcl_ls3d writes for a point format with `extra_bytes` per record: POINT10,
/// GPSTIME11, RGB12, BYTE version 2 for formats 0–5; POINT14, RGB14 / RGBNIR14, BYTE14 version 3
/// for 6–10. Wave packets are not written (formats 4, 5, 9, 10 are refused before this).
LaszipVlr
defaultLaszipVlr(int point_format, std::size_t extra_bytes, std::uint32_t chunk_size = 50000);

/// \brief Decodes the point records of one chunk. One object per thread: it holds the models.
class ChunkDecoder
{
public:
  virtual ~ChunkDecoder() = default;
  /// Decodes `count` records (record length · count bytes into `out`) from the chunk's bytes
  /// [begin, end). Returns the bytes the chunk occupied (so a file without a chunk table can be
  /// walked), or 0 with a one-line reason when the chunk is corrupt or runs past `end`. The
  /// models are reset at the start of every call.
  virtual std::size_t
  decode(const std::uint8_t* begin, const std::uint8_t* end, std::size_t count, std::uint8_t* out,
         std::string& error) = 0;
};

/// \brief Encodes the point records of one chunk.
class ChunkEncoder
{
public:
  virtual ~ChunkEncoder() = default;
  /// Appends the chunk for `count` records at `records` to `out`.
  virtual void
  encode(const std::uint8_t* records, std::size_t count, std::vector<std::uint8_t>& out) = 0;
};

/// Coders for a validated item list: pointwise items (POINT10 …, versions 1–2) or layered items
/// (POINT14 …, versions 3–4), by the VLR's compressor. Null with a reason for an item list
/// neither family takes.
std::unique_ptr<ChunkDecoder>
makeChunkDecoder(const LaszipVlr& vlr, std::string& error);
std::unique_ptr<ChunkEncoder>
makeChunkEncoder(const LaszipVlr& vlr, std::string& error);

// The two families (pointwise_chunk_codec.cpp, layered_chunk_codec.cpp).
std::unique_ptr<ChunkDecoder>
makePointwiseChunkDecoder(const LaszipVlr& vlr, std::string& error);
std::unique_ptr<ChunkEncoder>
makePointwiseChunkEncoder(const LaszipVlr& vlr, std::string& error);
std::unique_ptr<ChunkDecoder>
makeLayeredChunkDecoder(const LaszipVlr& vlr, std::string& error);
std::unique_ptr<ChunkEncoder>
makeLayeredChunkEncoder(const LaszipVlr& vlr, std::string& error);

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
