/// \file ply_header.cpp
/// \brief The PLY header: "ply", format, element / property / comment / obj_info lines,
///        end_header; strict counts and type names (see ply_io.h).

#include "ply_header.h"
#include "header_comments.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace pcl_ls3d {
namespace io {
namespace detail {

bool
plyFail(std::string& error, const std::string& message)
{
  error = "PLY " + message;
  return false;
}

std::size_t
PlyElement::minimumBytes() const
{
  std::size_t bytes = 0;
  for (const auto& p : properties)
    bytes += scalarSize(p.list ? p.count_type : p.type);
  return bytes;
}

bool
PlyElement::hasList() const
{
  return std::any_of(properties.begin(), properties.end(), [](const auto& p) { return p.list; });
}

namespace {

constexpr std::size_t kMaxElements = 1024, kMaxProperties = 4096;

bool
scalarOf(std::string_view name, Scalar& type)
{
  static const std::pair<const char*, Scalar> kTypes[] = {
      {"char", Scalar::Int8},      {"int8", Scalar::Int8},       {"uchar", Scalar::UInt8},
      {"uint8", Scalar::UInt8},    {"short", Scalar::Int16},     {"int16", Scalar::Int16},
      {"ushort", Scalar::UInt16},  {"uint16", Scalar::UInt16},   {"int", Scalar::Int32},
      {"int32", Scalar::Int32},    {"uint", Scalar::UInt32},     {"uint32", Scalar::UInt32},
      {"float", Scalar::Float32},  {"float32", Scalar::Float32}, {"double", Scalar::Float64},
      {"float64", Scalar::Float64}};
  for (const auto& [n, t] : kTypes)
    if (name == n) {
      type = t;
      return true;
    }
  return false;
}

bool
isInteger(Scalar t)
{
  return t != Scalar::Float32 && t != Scalar::Float64;
}

bool
propertyLine(const std::vector<std::string_view>& t, PlyHeader& h, std::string& error)
{
  if (h.elements.empty())
    return plyFail(error, "header: a property before any element");
  PlyElement& e = h.elements.back();
  if (e.properties.size() >= kMaxProperties)
    return plyFail(error, "header: more than 4096 properties in element " + quote(e.name));
  PlyProperty p;
  const bool list = t.size() == 5 && t[1] == "list";
  if (!(list || t.size() == 3))
    return plyFail(error, "header: malformed property line for element " + quote(e.name));
  p.list = list;
  p.name = std::string(t.back());
  if (!scalarOf(t[list ? 3 : 1], p.type))
    return plyFail(error, "header: unknown property type " + quote(t[list ? 3 : 1]));
  if (list && (!scalarOf(t[2], p.count_type) || !isInteger(p.count_type)))
    return plyFail(error, "header: list count type " + quote(t[2]) + " is not an integer type");
  e.properties.push_back(p);
  return true;
}

bool
headerLine(const std::vector<std::string_view>& t, PlyHeader& h, bool& has_format, std::string& error)
{
  const std::string_view key = t[0];
  if (key == "comment" || key == "obj_info")
    return true;
  if (key == "format") {
    if (has_format || t.size() != 3)
      return plyFail(error, "header: malformed or repeated format line");
    if (t[1] == "ascii")
      h.format = PlyFormat::Ascii;
    else if (t[1] == "binary_little_endian")
      h.format = PlyFormat::BinaryLittleEndian;
    else if (t[1] == "binary_big_endian")
      h.format = PlyFormat::BinaryBigEndian;
    else
      return plyFail(error, "header: unknown format " + quote(t[1]));
    has_format = true;
    return true;
  }
  if (key == "element") {
    PlyElement e;
    if (t.size() != 3 || h.elements.size() >= kMaxElements)
      return plyFail(error, "header: malformed element line (or more than 1024 elements)");
    e.name = std::string(t[1]);
    if (!parseCount(t[2], std::numeric_limits<std::int64_t>::max(), e.count))
      return plyFail(error, "header: element " + quote(e.name) + " count " + quote(t[2]) +
                                " is not an integer in 0.." +
                                std::to_string(std::numeric_limits<std::int64_t>::max()));
    h.elements.push_back(e);
    return true;
  }
  if (key == "property")
    return propertyLine(t, h, error);
  return plyFail(error, "header: unknown line starting with " + quote(key));
}

}  // namespace

bool
parsePlyHeader(const std::uint8_t* data, std::size_t size, PlyHeader& h, std::string& error)
{
  const char* text = reinterpret_cast<const char*>(data);
  std::vector<std::string_view> tokens;
  std::size_t pos = 0;
  bool has_format = false;
  while (pos < size) {
    const void* nl = std::memchr(text + pos, '\n', size - pos);
    const std::size_t end = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - text) : size;
    const std::string_view line(text + pos, end - pos);
    splitTokens(line, tokens);
    pos = nl ? end + 1 : size;
    ++h.header_lines;
    firstCommentValue(line, "comment pcl_ls3d crs ", h.crs_wkt);  // plyCrsLine()
    if (h.header_lines == 1) {
      if (tokens.size() != 1 || tokens[0] != "ply")
        return plyFail(error, "file does not start with a \"ply\" line");
      continue;
    }
    if (tokens.empty())
      continue;
    if (tokens[0] == "end_header") {
      if (!has_format)
        return plyFail(error, "header has no format line");
      h.data_offset = pos;
      return true;
    }
    if (!headerLine(tokens, h, has_format, error))
      return false;
  }
  return plyFail(error, "header has no end_header line (truncated or not a PLY file)");
}

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
