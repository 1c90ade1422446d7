/// \file point_fields.cpp
/// \brief Typed scalars, field-name mapping and small text helpers shared by the PCD/PLY readers.

#include "point_fields.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

namespace pcl_ls3d {
namespace io {
namespace detail {

namespace {

template <typename T>
double
load(const std::uint8_t* p, bool big_endian)
{
  std::uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (big_endian)
    std::reverse(bytes, bytes + sizeof(T));
  T v;
  std::memcpy(&v, bytes, sizeof(T));
  return static_cast<double>(v);
}

template <typename T>
T
clampTo(double v)
{
  if (!(v > 0.0))
    return 0;
  const double hi = static_cast<double>(std::numeric_limits<T>::max());
  return static_cast<T>(v >= hi ? hi : std::round(v));
}

}  // namespace

std::size_t
scalarSize(Scalar type)
{
  switch (type) {
  case Scalar::Int8:
  case Scalar::UInt8:
    return 1;
  case Scalar::Int16:
  case Scalar::UInt16:
    return 2;
  case Scalar::Int32:
  case Scalar::UInt32:
  case Scalar::Float32:
    return 4;
  default:
    return 8;
  }
}

double
readScalar(const std::uint8_t* p, Scalar type, bool big_endian)
{
  switch (type) {
  case Scalar::Int8:
    return load<std::int8_t>(p, false);
  case Scalar::UInt8:
    return load<std::uint8_t>(p, false);
  case Scalar::Int16:
    return load<std::int16_t>(p, big_endian);
  case Scalar::UInt16:
    return load<std::uint16_t>(p, big_endian);
  case Scalar::Int32:
    return load<std::int32_t>(p, big_endian);
  case Scalar::UInt32:
    return load<std::uint32_t>(p, big_endian);
  case Scalar::Int64:
    return load<std::int64_t>(p, big_endian);
  case Scalar::UInt64:
    return load<std::uint64_t>(p, big_endian);
  case Scalar::Float32:
    return load<float>(p, big_endian);
  default:
    return load<double>(p, big_endian);
  }
}

std::vector<Attribute>
mapAttributes(const std::vector<std::string>& names, std::vector<std::string>& mapped, bool label_is_class)
{
  static const std::pair<const char*, Attribute> kNames[] = {
      {"x", Attribute::X},
      {"y", Attribute::Y},
      {"z", Attribute::Z},
      {"intensity", Attribute::Intensity},
      {"gps_time", Attribute::GpsTime},
      {"point_source_id", Attribute::PointSourceId},
      {"classification", Attribute::Classification},
      {"label", Attribute::Classification},
      {"return_number", Attribute::ReturnNumber},
      {"number_of_returns", Attribute::NumberOfReturns}};
  const bool has_classification = std::find(names.begin(), names.end(), "classification") != names.end();
  std::vector<Attribute> out(names.size(), Attribute::None);
  mapped.clear();
  for (const auto& [name, attribute] : kNames) {
    if (std::strcmp(name, "label") == 0 && (has_classification || !label_is_class))
      continue;
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end())
      continue;
    out[static_cast<std::size_t>(it - names.begin())] = attribute;
    mapped.push_back(name);
  }
  return out;
}

bool
hasXyz(const std::vector<Attribute>& attributes)
{
  int found = 0;
  for (Attribute a : attributes)
    found += a == Attribute::X || a == Attribute::Y || a == Attribute::Z;
  return found == 3;
}

void
setAttribute(Attribute a, double value, PointLiDAR& point, double* xyz)
{
  switch (a) {
  case Attribute::X:
    xyz[0] = value;
    break;
  case Attribute::Y:
    xyz[1] = value;
    break;
  case Attribute::Z:
    xyz[2] = value;
    break;
  case Attribute::Intensity:
    point.intensity = static_cast<float>(value);
    break;
  case Attribute::GpsTime:
    point.gps_time = value;
    break;
  case Attribute::PointSourceId:
    point.point_source_id = clampTo<std::uint16_t>(value);
    break;
  case Attribute::Classification:
    point.classification = clampTo<std::uint8_t>(value);
    break;
  case Attribute::ReturnNumber:
    point.return_number = clampTo<std::uint8_t>(value);
    break;
  case Attribute::NumberOfReturns:
    point.number_of_returns = clampTo<std::uint8_t>(value);
    break;
  default:
    break;
  }
}

std::string
printable(std::string_view text)
{
  std::string out(text);
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      c = '?';
  return out;
}

std::string
clip(std::string_view text, std::size_t max_chars)
{
  return printable(text.substr(0, max_chars));
}

std::string
quote(std::string_view text, std::size_t max_chars)
{
  if (text.size() <= max_chars)
    return "'" + clip(text, max_chars) + "'";
  return "'" + clip(text, max_chars) + "...' (" + std::to_string(text.size()) + " characters)";
}

bool
parseCount(std::string_view text, std::uint64_t max, std::uint64_t& value)
{
  if (text.empty() || text.size() > 20 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return false;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), value);
  return r.ec == std::errc() && value <= max;
}

bool
parseDouble(std::string_view text, double& value)
{
  if (!text.empty() && text[0] == '+') {
    text.remove_prefix(1);
    if (!text.empty() && text[0] == '-')
      return false;
  }
  const auto r = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && r.ec == std::errc() && r.ptr == text.data() + text.size();
}

void
splitTokens(std::string_view line, std::vector<std::string_view>& tokens)
{
  tokens.clear();
  std::size_t i = 0;
  const auto separator = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (i < line.size()) {
    while (i < line.size() && separator(line[i]))
      ++i;
    const std::size_t b = i;
    while (i < line.size() && !separator(line[i]))
      ++i;
    if (i > b)
      tokens.push_back(line.substr(b, i - b));
  }
}

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
