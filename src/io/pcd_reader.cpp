/// \file pcd_reader.cpp
/// \brief PCD reader: the header is validated and its point count checked against the bytes
///        present before anything is allocated; then one pass over the ASCII lines, the binary
///        records or the decompressed field blocks (see pcd_io.h).

#include <pcl_ls3d/io/pcd_io.h>

#include "local_origin.h"
#include "pcd_header.h"
#include "point_fields.h"

#include <pcl/io/lzf.h>

#include <cstring>
#include <limits>

namespace pcl_ls3d {
namespace io {

namespace {

using detail::Attribute;
using detail::PcdBody;
using detail::PcdHeader;
using detail::Scalar;

constexpr std::uint64_t kMaxU32 = std::numeric_limits<std::uint32_t>::max();

bool
fail(std::string& error, const std::string& message)
{
  return detail::pcdFail(error, message);
}

/// Fields that fill something, with their byte offsets in a record and token index on a line.
struct MappedField
{
  Attribute attribute;
  Scalar type;
  std::size_t offset, token;
  std::size_t block, stride;  ///< binary_compressed: start of the field's block, bytes per point
};

std::vector<MappedField>
mappedFields(const PcdHeader& h, const std::vector<Attribute>& attributes)
{
  std::vector<MappedField> out;
  std::size_t offset = 0, token = 0, block = 0;
  for (std::size_t i = 0; i < h.names.size(); ++i) {
    const std::size_t bytes = h.sizes[i] * h.counts[i];
    if (attributes[i] != Attribute::None)
      out.push_back({attributes[i], h.types[i], offset, token, block, bytes});
    offset += bytes;
    token += h.counts[i];
    if (h.names[i] != "_")
      block += bytes * h.points;  // binary_compressed stores field after field
  }
  return out;
}

/// "header says N points, but <what follows> (room for at most K)".
std::string
claim(const PcdHeader& h, const std::string& what, std::uint64_t room)
{
  return "header says " + std::to_string(h.points) + " points, but " + what + " (room for at most " +
         std::to_string(room) + ")";
}

bool
readAscii(const char* text, std::size_t size, std::size_t line_number, const PcdHeader& h,
          const std::vector<MappedField>& fields, pcl::PointCloud<PointLiDAR>& cloud,
          std::vector<double>& xyz, std::string& error)
{
  std::vector<std::string_view> tokens;
  std::size_t pos = 0, n = 0;
  while (pos < size && n < h.points) {
    const void* nl = std::memchr(text + pos, '\n', size - pos);
    const std::size_t end = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - text) : size;
    detail::splitTokens(std::string_view(text + pos, end - pos), tokens);
    pos = nl ? end + 1 : size;
    ++line_number;
    if (tokens.empty())
      continue;
    const std::string at = "line " + std::to_string(line_number);
    if (tokens.size() != h.values)
      return fail(error, at + ": " + std::to_string(tokens.size()) + " values, expected " +
                             std::to_string(h.values));
    for (const MappedField& f : fields) {
      double v = 0.0;
      if (!detail::parseDouble(tokens[f.token], v))
        return fail(error, at + ", value " + std::to_string(f.token + 1) + ": cannot parse " +
                               detail::quote(tokens[f.token]) + " as a number");
      detail::setAttribute(f.attribute, v, cloud[n], &xyz[3 * n]);
    }
    ++n;
  }
  if (n != h.points)
    return fail(error,
                "header says " + std::to_string(h.points) + " points, the data has " + std::to_string(n));
  return true;
}

/// binary_compressed: two uint32 sizes, then LZF data holding field after field.
bool
decompress(const std::uint8_t* body, std::size_t size, const PcdHeader& h, std::vector<std::uint8_t>& out,
           std::string& error)
{
  if (size < 8)
    return fail(error, "binary_compressed data shorter than its 8-byte size block");
  std::uint32_t compressed = 0, uncompressed = 0;
  std::memcpy(&compressed, body, 4);
  std::memcpy(&uncompressed, body + 4, 4);
  if (h.packed != 0 && h.points > kMaxU32 / h.packed)
    return fail(error, claim(h, "a binary_compressed size block has 32 bits", kMaxU32 / h.packed));
  const std::uint64_t expected = h.points * h.packed;
  if (uncompressed != expected)
    return fail(error, "binary_compressed size block says " + std::to_string(uncompressed) +
                           " bytes, the header's points need " + std::to_string(expected));
  if (compressed > size - 8)
    return fail(error, "compressed block of " + std::to_string(compressed) + " bytes, only " +
                           std::to_string(size - 8) + " follow");
  if (expected == 0)
    return true;
  if (compressed == 0 || expected / 100 > compressed)  // LZF expands at most ~88 times
    return fail(error, claim(h, std::to_string(compressed) + " LZF bytes expand at most 100 times",
                             compressed * 100ull / h.packed));
  out.resize(expected);
  if (pcl::lzfDecompress(body + 8, compressed, out.data(), uncompressed) != uncompressed)
    return fail(error, "binary_compressed data is corrupt (LZF)");
  return true;
}

}  // namespace

bool
readPcd(const std::uint8_t* data, std::size_t size, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
        std::string& error, const LoadOptions& options)
{
  info = CloudInfo();
  info.format = "pcd";
  cloud.clear();
  PcdHeader h;
  if (!detail::parsePcdHeader(data, size, h, error))
    return false;
  info.segments_file = h.segments_marker;
  const std::vector<Attribute> attributes = detail::mapAttributes(h.names, info.fields, !h.segments_marker);
  if (!detail::hasXyz(attributes))
    return fail(error, "file has no x, y, z fields");
  const std::vector<MappedField> fields = mappedFields(h, attributes);
  const std::uint8_t* body = data + h.data_offset;
  const std::size_t left = size - h.data_offset;
  std::vector<std::uint8_t> unpacked;
  if (h.body == PcdBody::Binary && h.points > left / h.record)
    return fail(error, claim(h,
                             "only " + std::to_string(left) + " bytes of " + std::to_string(h.record) +
                                 "-byte records follow",
                             left / h.record));
  if (h.body == PcdBody::Ascii && h.points > (left + 1) / (2 * h.values))
    return fail(error, claim(h, "only " + std::to_string(left) + " bytes of ASCII data follow",
                             (left + 1) / (2 * h.values)));
  if (h.body == PcdBody::Compressed && !decompress(body, left, h, unpacked, error))
    return false;

  cloud.resize(h.points);
  std::vector<double> xyz(3 * h.points, 0.0);
  if (h.body == PcdBody::Ascii) {
    std::size_t header_lines = 0;
    for (std::size_t i = 0; i < h.data_offset; ++i)
      header_lines += data[i] == '\n';
    if (!readAscii(reinterpret_cast<const char*>(body), left, header_lines, h, fields, cloud, xyz, error)) {
      cloud.clear();
      return false;
    }
  } else {
    const bool packed = h.body == PcdBody::Compressed;
    for (std::size_t i = 0; i < h.points; ++i)
      for (const MappedField& f : fields) {
        const std::uint8_t* p =
            packed ? unpacked.data() + f.block + i * f.stride : body + i * h.record + f.offset;
        detail::setAttribute(f.attribute, detail::readScalar(p, f.type, false), cloud[i], &xyz[3 * i]);
      }
  }
  // A recorded origin is the file's own local frame: kept unless another one is forced.
  LoadOptions frame = options;
  if (h.has_origin && !options.use_origin) {
    frame.use_origin = true;
    frame.origin = h.origin;
  }
  info.file_origin = h.origin;
  info.has_file_origin = h.has_origin;
  info.file_crs_wkt = h.crs_wkt;
  return detail::applyLocalOrigin(xyz, cloud, info, frame, error, h.origin);
}

}  // namespace io
}  // namespace pcl_ls3d
