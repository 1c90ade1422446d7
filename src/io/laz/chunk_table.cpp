/// \file chunk_table.cpp
/// \brief Reading and writing the LASzip chunk table (chunk_table.h).

#include "chunk_table.h"

#include "integer_compressor.h"

#include "io/las_format.h"

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

constexpr std::size_t kTableHead = 8;  // version, chunk count

}  // namespace

bool
readChunkTable(const std::uint8_t* data, std::size_t size, std::uint64_t offset, bool variable,
               std::uint64_t max_chunks, ChunkTable& table, std::string& error)
{
  table = ChunkTable();
  if (offset > size || size - offset < kTableHead) {
    error = "the chunk table offset " + std::to_string(offset) + " lies outside the " + std::to_string(size) +
            "-byte file";
    return false;
  }
  const std::uint8_t* p = data + offset;
  const auto version = las::get<std::uint32_t>(p);
  const auto count = las::get<std::uint32_t>(p + 4);
  if (version != 0) {
    error = "the chunk table has version " + std::to_string(version) + " (only 0 exists)";
    return false;
  }
  if (count > max_chunks) {
    error = "the chunk table lists " + std::to_string(count) + " chunks, more than the " +
            std::to_string(max_chunks) + " the compressed bytes can hold";
    return false;
  }
  table.bytes.resize(count);
  if (variable)
    table.points.resize(count);
  if (count == 0)
    return true;
  ArithmeticDecoder dec(p + kTableHead, data + size);
  IntegerCompressor ic(32, 2);
  std::uint32_t points = 0, bytes = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (variable)
      table.points[i] = points =
          static_cast<std::uint32_t>(ic.decompress(dec, static_cast<std::int32_t>(points), 0));
    bytes = static_cast<std::uint32_t>(ic.decompress(dec, static_cast<std::int32_t>(bytes), 1));
    table.bytes[i] = bytes;
    if (dec.overrun() != 0) {
      error = "the chunk table is truncated after " + std::to_string(i) + " of " + std::to_string(count) +
              " chunks";
      return false;
    }
  }
  return true;
}

std::vector<std::uint8_t>
writeChunkTable(const ChunkTable& table, bool variable)
{
  const auto count = static_cast<std::uint32_t>(table.bytes.size());
  std::vector<std::uint8_t> out(kTableHead, 0);
  las::put<std::uint32_t>(out.data() + 4, count);
  if (count == 0)
    return out;
  ArithmeticEncoder enc;
  enc.start();
  IntegerCompressor ic(32, 2);
  for (std::uint32_t i = 0; i < count; ++i) {
    if (variable)
      ic.compress(enc, i ? static_cast<std::int32_t>(table.points[i - 1]) : 0,
                  static_cast<std::int32_t>(table.points[i]), 0);
    ic.compress(enc, i ? static_cast<std::int32_t>(table.bytes[i - 1]) : 0,
                static_cast<std::int32_t>(table.bytes[i]), 1);
  }
  const std::vector<std::uint8_t>& coded = enc.finish();
  out.insert(out.end(), coded.begin(), coded.end());
  return out;
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
