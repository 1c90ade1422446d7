/// \file pcd_header.cpp
/// \brief The PCD header: strict keywords and counts, FIELDS/SIZE/TYPE/COUNT agreement, WIDTH x
///        HEIGHT = POINTS (see pcd_io.h).

#include "pcd_header.h"
#include "header_comments.h"

#include <pcl_ls3d/io/pcd_io.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>

namespace pcl_ls3d {
namespace io {
namespace detail {

bool
pcdFail(std::string& error, const std::string& message)
{
  error = "PCD " + message;
  return false;
}

namespace {

const auto& fail = pcdFail;

constexpr std::size_t kMaxFields = 4096;
constexpr std::uint64_t kMaxCount = 1u << 20;
constexpr std::uint64_t kMaxU32 = std::numeric_limits<std::uint32_t>::max();

/// The origin line's tokens: "#", "pcl_ls3d", "origin" and three finite numbers.
PcdOriginLine
parseOriginTokens(const std::vector<std::string_view>& t, Eigen::Vector3d& origin)
{
  if (t.size() < 3 || t[0] != "#" || t[1] != "pcl_ls3d" || t[2] != "origin")
    return PcdOriginLine::NotOrigin;
  Eigen::Vector3d o;
  if (t.size() != 6 || !parseDouble(t[3], o[0]) || !parseDouble(t[4], o[1]) || !parseDouble(t[5], o[2]) ||
      !o.allFinite())
    return PcdOriginLine::Malformed;
  origin = o;
  return PcdOriginLine::Origin;
}

bool
scalarOf(char kind, std::size_t size, Scalar& type)
{
  static const Scalar kSigned[] = {Scalar::Int8, Scalar::Int16, Scalar::Int32, Scalar::Int64};
  static const Scalar kUnsigned[] = {Scalar::UInt8, Scalar::UInt16, Scalar::UInt32, Scalar::UInt64};
  const int index = size == 1 ? 0 : size == 2 ? 1 : size == 4 ? 2 : size == 8 ? 3 : -1;
  if (kind == 'F' && (size == 4 || size == 8))
    type = size == 4 ? Scalar::Float32 : Scalar::Float64;
  else if ((kind == 'I' || kind == 'U') && index >= 0)
    type = kind == 'I' ? kSigned[index] : kUnsigned[index];
  else
    return false;
  return true;
}

/// One list of per-field numbers (SIZE or COUNT): as many as FIELDS, each in [1, max].
bool
perFieldCounts(const std::vector<std::string_view>& t, std::size_t fields, std::uint64_t max,
               std::vector<std::uint64_t>& out, std::string& error)
{
  if (fields == 0 || t.size() - 1 != fields)
    return fail(error, "header: " + std::string(t[0]) + " has " + std::to_string(t.size() - 1) +
                           " entries for " + std::to_string(fields) + " FIELDS");
  out.clear();
  for (std::size_t i = 1; i < t.size(); ++i) {
    std::uint64_t v = 0;
    if (!parseCount(t[i], max, v) || v == 0)
      return fail(error, "header: " + std::string(t[0]) + " entry " + quote(t[i]) +
                             " is not an integer in 1.." + std::to_string(max));
    out.push_back(v);
  }
  return true;
}

bool
headerLine(const std::vector<std::string_view>& t, PcdHeader& h, std::string& error)
{
  const std::string_view key = t[0];
  std::uint64_t v = 0;
  if (key == "VERSION" || key == "VIEWPOINT")
    return true;
  if (key == "FIELDS" || key == "COLUMNS") {
    if (!h.names.empty() || t.size() < 2 || t.size() - 1 > kMaxFields)
      return fail(error, "header: FIELDS repeated, empty or longer than 4096 names");
    for (std::size_t i = 1; i < t.size(); ++i)
      h.names.emplace_back(t[i]);
    return true;
  }
  if (key == "SIZE" || key == "COUNT") {
    std::vector<std::uint64_t> values;
    if (!perFieldCounts(t, h.names.size(), key == "SIZE" ? 8 : kMaxCount, values, error))
      return false;
    if (key == "SIZE")
      h.sizes.assign(values.begin(), values.end());
    else
      h.counts = values;
    return true;
  }
  if (key == "TYPE") {
    if (h.names.empty() || t.size() - 1 != h.names.size())
      return fail(error, "header: TYPE does not have one entry per field");
    for (std::size_t i = 1; i < t.size(); ++i) {
      if (t[i].size() != 1)
        return fail(error, "header: TYPE entry " + quote(t[i]) + " is not F, I or U");
      h.kinds.push_back(t[i][0]);
    }
    return true;
  }
  const bool dims = key == "WIDTH" || key == "HEIGHT" || key == "POINTS";
  if (dims) {
    const std::uint64_t max = key == "POINTS" ? std::numeric_limits<std::uint64_t>::max() : kMaxU32;
    if (t.size() != 2 || !parseCount(t[1], max, v))
      return fail(error,
                  "header: " + std::string(key) + " " + quote(t.size() > 1 ? t[1] : "") + " is not a count");
    bool& seen = key == "WIDTH" ? h.has_width : key == "HEIGHT" ? h.has_height : h.has_points;
    (key == "WIDTH" ? h.width : key == "HEIGHT" ? h.height : h.points) = v;
    if (seen)
      return fail(error, "header: " + std::string(key) + " given twice");
    seen = true;
    return true;
  }
  if (key == "DATA") {
    const std::string_view kind = t.size() > 1 ? t[1] : "";
    if (kind == "ascii")
      h.body = PcdBody::Ascii;
    else if (kind == "binary")
      h.body = PcdBody::Binary;
    else if (kind == "binary_compressed")
      h.body = PcdBody::Compressed;
    else
      return fail(error, "header: DATA " + quote(kind) + " is not ascii, binary or binary_compressed");
    return true;
  }
  return fail(error, "header: unknown line starting with " + quote(key));
}

/// Types, record sizes and WIDTH x HEIGHT = POINTS (as PCL: no WIDTH means POINTS x 1).
bool
finishHeader(PcdHeader& h, std::string& error)
{
  const std::size_t n = h.names.size();
  if (n == 0 || h.sizes.size() != n || h.kinds.size() != n)
    return fail(error, "header: FIELDS, SIZE and TYPE are required and must agree");
  if (h.counts.empty())
    h.counts.assign(n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    Scalar type;
    if (!scalarOf(h.kinds[i], h.sizes[i], type))
      return fail(error, "header: field " + quote(h.names[i]) + " has TYPE " + std::string(1, h.kinds[i]) +
                             " with SIZE " + std::to_string(h.sizes[i]));
    h.types.push_back(type);
    h.record += h.sizes[i] * h.counts[i];
    h.values += h.counts[i];
    if (h.names[i] != "_")
      h.packed += h.sizes[i] * h.counts[i];
  }
  if (h.record > kMaxU32)
    return fail(error, "header: a point of " + std::to_string(h.record) + " bytes is too large");
  if (!h.has_height)
    h.height = 1;
  if (!h.has_width) {
    if (!h.has_points || h.height != 1)
      return fail(error, "header: no WIDTH");
    h.width = h.points;
  }
  const bool overflow = h.height != 0 && h.width > std::numeric_limits<std::uint64_t>::max() / h.height;
  if (!h.has_points && !overflow)
    h.points = h.width * h.height;
  if (overflow || h.width * h.height != h.points)
    return fail(error, "header: WIDTH " + std::to_string(h.width) + " x HEIGHT " + std::to_string(h.height) +
                           " is not POINTS " + std::to_string(h.points));
  return true;
}

/// A comment line: records the origin if it is a "# pcl_ls3d origin" line (pcd_io.h); false only
/// for a malformed or repeated one, whose origin cannot be trusted.
bool
originComment(const std::vector<std::string_view>& tokens, PcdHeader& h, std::string& error)
{
  Eigen::Vector3d origin;
  switch (parseOriginTokens(tokens, origin)) {
  case PcdOriginLine::NotOrigin:
    return true;
  case PcdOriginLine::Malformed:
    return fail(error, "header: '# pcl_ls3d origin' is not followed by three finite numbers");
  case PcdOriginLine::Origin:
    break;
  }
  if (h.has_origin)
    return fail(error, "header: '# pcl_ls3d origin' given twice");
  h.has_origin = true;
  h.origin = origin;
  return true;
}

}  // namespace

bool
parsePcdHeader(const std::uint8_t* data, std::size_t size, PcdHeader& h, std::string& error)
{
  const char* text = reinterpret_cast<const char*>(data);
  std::vector<std::string_view> tokens;
  std::size_t pos = 0;
  while (pos < size) {
    const void* nl = std::memchr(text + pos, '\n', size - pos);
    const std::size_t end = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - text) : size;
    const std::string_view line(text + pos, end - pos);
    splitTokens(line, tokens);
    pos = nl ? end + 1 : size;
    if (!tokens.empty() && tokens[0][0] == '#' && !originComment(tokens, h, error))
      return false;
    if (!tokens.empty() && tokens[0][0] == '#') {
      firstCommentValue(line, "# pcl_ls3d crs ", h.crs_wkt);  // pcdCrsLine()
      h.segments_marker = h.segments_marker || isPcdSegmentsMarkerLine(line);
    }
    if (tokens.empty() || tokens[0][0] == '#')
      continue;
    if (!headerLine(tokens, h, error))
      return false;
    if (tokens[0] == "DATA") {
      h.data_offset = pos;
      return finishHeader(h, error);
    }
  }
  return fail(error, "header has no DATA line (truncated or not a PCD file)");
}

}  // namespace detail

std::string
pcdCrsLine(const std::string& wkt)
{
  return detail::oneLineComment("# pcl_ls3d crs ", wkt);
}

std::string
pcdOriginLine(const Eigen::Vector3d& origin)
{
  char line[128];
  std::snprintf(line, sizeof(line), "# pcl_ls3d origin %.17g %.17g %.17g", origin.x(), origin.y(),
                origin.z());
  return line;
}

bool
isPcdSegmentsMarkerLine(std::string_view line)
{
  return detail::withoutLineEnd(line) == kPcdSegmentsMarker;
}

PcdOriginLine
parsePcdOriginLine(std::string_view line, Eigen::Vector3d& origin)
{
  std::vector<std::string_view> tokens;
  detail::splitTokens(line, tokens);
  return detail::parseOriginTokens(tokens, origin);
}

}  // namespace io
}  // namespace pcl_ls3d
