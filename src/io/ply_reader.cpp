/// \file ply_reader.cpp
/// \brief PLY reader: header checked first, the vertex count checked against the bytes present,
///        then one pass over the vertex items; elements after the vertices are not read
///        (see ply_io.h).

#include <pcl_ls3d/io/ply_io.h>

#include "header_comments.h"
#include "local_origin.h"
#include "ply_header.h"

#include <cmath>
#include <cstring>

namespace pcl_ls3d {
namespace io {

namespace {

using detail::Attribute;
using detail::PlyElement;
using detail::PlyFormat;
using detail::PlyHeader;
using detail::Scalar;

bool
fail(std::string& error, const std::string& message)
{
  return detail::plyFail(error, message);
}

/// A list count: a non-negative whole number.
bool
validListCount(double v)
{
  return v >= 0.0 && v == std::floor(v) && v <= 4294967295.0;
}

/// The binary data after the header, read front to back.
struct BinaryCursor
{
  const std::uint8_t* data;
  std::size_t size, pos;
  bool big_endian;

  bool
  scalar(Scalar type, double& v)
  {
    const std::size_t n = detail::scalarSize(type);
    if (size - pos < n)
      return false;
    v = detail::readScalar(data + pos, type, big_endian);
    pos += n;
    return true;
  }

  bool
  skip(std::uint64_t bytes)
  {
    if (bytes > size - pos)
      return false;
    pos += static_cast<std::size_t>(bytes);
    return true;
  }
};

/// The ASCII data after the header, one non-blank line at a time.
struct AsciiCursor
{
  const char* text;
  std::size_t size, pos, line;
  std::vector<std::string_view> tokens;

  bool
  next()
  {
    while (pos < size) {
      const void* nl = std::memchr(text + pos, '\n', size - pos);
      const std::size_t end = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - text) : size;
      detail::splitTokens(std::string_view(text + pos, end - pos), tokens);
      pos = nl ? end + 1 : size;
      ++line;
      if (!tokens.empty())
        return true;
    }
    return false;
  }
};

/// One binary item; `attributes` (one per property) is null for a skipped element.
bool
binaryItem(const PlyElement& e, const std::vector<Attribute>* attributes, BinaryCursor& c, PointLiDAR& point,
           double* xyz, std::string& error)
{
  for (std::size_t k = 0; k < e.properties.size(); ++k) {
    const auto& p = e.properties[k];
    double v = 0.0;
    if (!c.scalar(p.list ? p.count_type : p.type, v))
      return fail(error, "element " + detail::quote(e.name) + ": data ends inside an item");
    if (p.list) {
      if (!validListCount(v) || !c.skip(static_cast<std::uint64_t>(v) * detail::scalarSize(p.type)))
        return fail(error, "element " + detail::quote(e.name) + ": list " + detail::quote(p.name) +
                               " count " + std::to_string(v) + " runs past the data");
    } else if (attributes)
      detail::setAttribute((*attributes)[k], v, point, xyz);
  }
  return true;
}

/// One ASCII item (the cursor's current line).
bool
asciiItem(const PlyElement& e, const std::vector<Attribute>* attributes, const AsciiCursor& c,
          PointLiDAR& point, double* xyz, std::string& error)
{
  const std::string at = "line " + std::to_string(c.line) + ": ";
  std::size_t t = 0;
  for (std::size_t k = 0; k < e.properties.size(); ++k) {
    const auto& p = e.properties[k];
    double v = 0.0;
    if (t >= c.tokens.size())
      return fail(error, at + "too few values for element " + detail::quote(e.name));
    const bool parse = p.list || (attributes && (*attributes)[k] != Attribute::None);
    if (parse && !detail::parseDouble(c.tokens[t], v))
      return fail(error, at + "cannot parse " + detail::quote(c.tokens[t]) + " as a number");
    ++t;
    if (p.list) {
      if (!validListCount(v) || v > static_cast<double>(c.tokens.size() - t))
        return fail(error, at + "list " + detail::quote(p.name) + " count " + detail::quote(c.tokens[t - 1]) +
                               " does not match the line");
      t += static_cast<std::size_t>(v);
    } else if (attributes)
      detail::setAttribute((*attributes)[k], v, point, xyz);
  }
  if (t != c.tokens.size())
    return fail(error, at + std::to_string(c.tokens.size()) + " values, element " + detail::quote(e.name) +
                           " has " + std::to_string(t));
  return true;
}

/// The largest count of `e` items the remaining data could hold.
std::uint64_t
room(const PlyElement& e, PlyFormat format, std::size_t left)
{
  if (format == PlyFormat::Ascii)
    return (left + 1) / (2 * e.properties.size());
  return left / e.minimumBytes();
}

bool
readElement(const PlyElement& e, const PlyHeader& h, const std::vector<Attribute>* attributes,
            BinaryCursor& b, AsciiCursor& a, pcl::PointCloud<PointLiDAR>& cloud, std::vector<double>& xyz,
            std::string& error)
{
  if (e.properties.empty())
    return true;
  const bool ascii = h.format == PlyFormat::Ascii;
  const std::uint64_t fits = room(e, h.format, ascii ? a.size - a.pos : b.size - b.pos);
  if (e.count > fits)
    return fail(error, "header says " + std::to_string(e.count) + " " + detail::clip(e.name) +
                           " items, the " + "data after it can hold at most " + std::to_string(fits));
  if (!ascii && !e.hasList() && !attributes) {
    b.skip(e.count * e.minimumBytes());  // fits: checked above
    return true;
  }
  if (attributes) {
    cloud.resize(e.count);
    xyz.assign(3 * e.count, 0.0);
  }
  PointLiDAR unused;
  double unused_xyz[3];
  for (std::uint64_t i = 0; i < e.count; ++i) {
    PointLiDAR& p = attributes ? cloud[i] : unused;
    double* x = attributes ? &xyz[3 * i] : unused_xyz;
    if (ascii && !a.next())
      return fail(error, "header says " + std::to_string(e.count) + " " + detail::clip(e.name) +
                             " items, the data ends after " + std::to_string(i));
    if (!(ascii ? asciiItem(e, attributes, a, p, x, error) : binaryItem(e, attributes, b, p, x, error)))
      return false;
  }
  return true;
}

}  // namespace

std::string
plyCrsLine(const std::string& wkt)
{
  return detail::oneLineComment("comment pcl_ls3d crs ", wkt);
}

bool
readPly(const std::uint8_t* data, std::size_t size, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
        std::string& error, const LoadOptions& options)
{
  info = CloudInfo();
  info.format = "ply";
  cloud.clear();
  PlyHeader h;
  if (!detail::parsePlyHeader(data, size, h, error))
    return false;
  info.file_crs_wkt = h.crs_wkt;
  std::size_t vertex = 0;
  while (vertex < h.elements.size() && h.elements[vertex].name != "vertex")
    ++vertex;
  if (vertex == h.elements.size())
    return fail(error, "file has no vertex element");
  const PlyElement& v = h.elements[vertex];
  std::vector<std::string> names;
  for (const auto& p : v.properties)
    names.push_back(p.list ? std::string() : p.name);
  const std::vector<Attribute> attributes = detail::mapAttributes(names, info.fields);
  if (!detail::hasXyz(attributes))
    return fail(error, "vertex element has no x, y, z properties");

  BinaryCursor b{data, size, h.data_offset, h.format == PlyFormat::BinaryBigEndian};
  AsciiCursor a{reinterpret_cast<const char*>(data), size, h.data_offset, h.header_lines, {}};
  std::vector<double> xyz;
  for (std::size_t i = 0; i <= vertex; ++i)
    if (!readElement(h.elements[i], h, i == vertex ? &attributes : nullptr, b, a, cloud, xyz, error)) {
      cloud.clear();
      return false;
    }
  return detail::applyLocalOrigin(xyz, cloud, info, options, error);
}

}  // namespace io
}  // namespace pcl_ls3d
