/// \file laszip_items.cpp
/// \brief The LASzip VLR: parsing with every field checked, writing, the default item list, and
///        the choice of chunk coder.

#include "laszip_items.h"

#include "io/las_format.h"

#include <sstream>

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

constexpr std::size_t kVlrFixedBytes = 34, kItemBytes = 6;

bool
isLayeredFormat(int point_format)
{
  return point_format >= 6;
}

/// The item versions this decoder implements, and whether the type belongs to the format family.
bool
itemSupported(const Item& item, bool layered, std::string& why)
{
  std::ostringstream s;
  switch (item.type) {
  case ItemType::Point10:
  case ItemType::GpsTime11:
  case ItemType::Rgb12:
  case ItemType::Byte:
    if (layered || item.version < 1 || item.version > 2)
      break;
    return true;
  case ItemType::Point14:
  case ItemType::Rgb14:
  case ItemType::RgbNir14:
  case ItemType::Byte14:
    if (!layered || item.version < 3 || item.version > 4)
      break;
    return true;
  case ItemType::Wavepacket13:
  case ItemType::Wavepacket14:
    why = "waveform packets (point formats 4, 5, 9, 10) are not supported in LAZ";
    return false;
  default:
    s << "the LASzip VLR names item type " << static_cast<int>(item.type)
      << ", which no LASzip writer uses for point records";
    why = s.str();
    return false;
  }
  s << "the LASzip VLR names item type " << static_cast<int>(item.type) << " version " << item.version
    << ", which this decoder does not implement for "
    << (layered ? "point formats 6-10" : "point formats 0-5");
  why = s.str();
  return false;
}

}  // namespace

std::size_t
LaszipVlr::recordLength() const
{
  std::size_t n = 0;
  for (const Item& item : items)
    n += item.size;
  return n;
}

bool
parseLaszipVlr(const std::uint8_t* data, std::size_t size, int point_format, std::size_t record_length,
               LaszipVlr& vlr, std::string& error)
{
  if (size < kVlrFixedBytes) {
    error = "the LASzip VLR is " + std::to_string(size) + " bytes, shorter than its 34-byte head";
    return false;
  }
  vlr = LaszipVlr();
  vlr.compressor = static_cast<Compressor>(las::get<std::uint16_t>(data));
  vlr.coder = las::get<std::uint16_t>(data + 2);
  vlr.version_major = data[4];
  vlr.version_minor = data[5];
  vlr.version_revision = las::get<std::uint16_t>(data + 6);
  vlr.options = las::get<std::uint32_t>(data + 8);
  vlr.chunk_size = las::get<std::uint32_t>(data + 12);
  vlr.special_evlr_count = las::get<std::int64_t>(data + 16);
  vlr.special_evlr_offset = las::get<std::int64_t>(data + 24);
  const std::size_t item_count = las::get<std::uint16_t>(data + 32);
  if (kVlrFixedBytes + kItemBytes * item_count > size) {
    error = "the LASzip VLR declares " + std::to_string(item_count) + " items but holds only " +
            std::to_string((size - kVlrFixedBytes) / kItemBytes);
    return false;
  }
  const bool layered = isLayeredFormat(point_format);
  const auto compressor = static_cast<std::uint16_t>(vlr.compressor);
  if (compressor < 1 || compressor > 3) {
    error = "the LASzip VLR names compressor " + std::to_string(compressor) +
            " (known: 1 pointwise, 2 pointwise-chunked, 3 layered-chunked)";
    return false;
  }
  if ((vlr.compressor == Compressor::LayeredChunked) != layered) {
    error = "the LASzip VLR's compressor " + std::to_string(compressor) + " does not fit point format " +
            std::to_string(point_format);
    return false;
  }
  if (vlr.coder != 0) {
    error = "the LASzip VLR names coder " + std::to_string(vlr.coder) + " (only 0, arithmetic, exists)";
    return false;
  }
  if (vlr.compressor != Compressor::Pointwise && vlr.chunk_size == 0) {
    error = "the LASzip VLR declares chunks of 0 points";
    return false;
  }
  for (std::size_t i = 0; i < item_count; ++i) {
    const std::uint8_t* p = data + kVlrFixedBytes + kItemBytes * i;
    Item item{static_cast<ItemType>(las::get<std::uint16_t>(p)), las::get<std::uint16_t>(p + 2),
              las::get<std::uint16_t>(p + 4)};
    if (!itemSupported(item, layered, error))
      return false;
    vlr.items.push_back(item);
  }
  if (vlr.items.empty() || vlr.recordLength() != record_length) {
    error = "the LASzip VLR's items cover " + std::to_string(vlr.recordLength()) + " bytes of a " +
            std::to_string(record_length) + "-byte point record";
    return false;
  }
  return true;
}

std::vector<std::uint8_t>
serializeLaszipVlr(const LaszipVlr& vlr)
{
  std::vector<std::uint8_t> out(kVlrFixedBytes + kItemBytes * vlr.items.size());
  las::put<std::uint16_t>(out.data(), static_cast<std::uint16_t>(vlr.compressor));
  las::put<std::uint16_t>(out.data() + 2, vlr.coder);
  out[4] = vlr.version_major;
  out[5] = vlr.version_minor;
  las::put<std::uint16_t>(out.data() + 6, vlr.version_revision);
  las::put<std::uint32_t>(out.data() + 8, vlr.options);
  las::put<std::uint32_t>(out.data() + 12, vlr.chunk_size);
  las::put<std::int64_t>(out.data() + 16, vlr.special_evlr_count);
  las::put<std::int64_t>(out.data() + 24, vlr.special_evlr_offset);
  las::put<std::uint16_t>(out.data() + 32, static_cast<std::uint16_t>(vlr.items.size()));
  for (std::size_t i = 0; i < vlr.items.size(); ++i) {
    std::uint8_t* p = out.data() + kVlrFixedBytes + kItemBytes * i;
    las::put<std::uint16_t>(p, static_cast<std::uint16_t>(vlr.items[i].type));
    las::put<std::uint16_t>(p + 2, vlr.items[i].size);
    las::put<std::uint16_t>(p + 4, vlr.items[i].version);
  }
  return out;
}

LaszipVlr
defaultLaszipVlr(int point_format, std::size_t extra_bytes, std::uint32_t chunk_size)
{
  LaszipVlr vlr;
  vlr.version_major = 3;  // the LASzip release whose layout this follows
  vlr.version_minor = 4;
  vlr.version_revision = 3;
  vlr.chunk_size = chunk_size;
  const auto extra = static_cast<std::uint16_t>(extra_bytes);
  if (!isLayeredFormat(point_format)) {
    vlr.compressor = Compressor::PointwiseChunked;
    vlr.items.push_back({ItemType::Point10, 20, 2});
    if (point_format == 1 || point_format == 3)
      vlr.items.push_back({ItemType::GpsTime11, 8, 2});
    if (point_format == 2 || point_format == 3)
      vlr.items.push_back({ItemType::Rgb12, 6, 2});
    if (extra != 0)
      vlr.items.push_back({ItemType::Byte, extra, 2});
  } else {
    vlr.compressor = Compressor::LayeredChunked;
    vlr.options = 0;
    vlr.items.push_back({ItemType::Point14, 30, 3});
    if (point_format == 7)
      vlr.items.push_back({ItemType::Rgb14, 6, 3});
    if (point_format == 8)
      vlr.items.push_back({ItemType::RgbNir14, 8, 3});
    if (extra != 0)
      vlr.items.push_back({ItemType::Byte14, extra, 3});
  }
  return vlr;
}

std::unique_ptr<ChunkDecoder>
makeChunkDecoder(const LaszipVlr& vlr, std::string& error)
{
  return vlr.compressor == Compressor::LayeredChunked ? makeLayeredChunkDecoder(vlr, error)
                                                      : makePointwiseChunkDecoder(vlr, error);
}

std::unique_ptr<ChunkEncoder>
makeChunkEncoder(const LaszipVlr& vlr, std::string& error)
{
  return vlr.compressor == Compressor::LayeredChunked ? makeLayeredChunkEncoder(vlr, error)
                                                      : makePointwiseChunkEncoder(vlr, error);
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
