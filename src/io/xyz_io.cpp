/// \file xyz_io.cpp
/// \brief ASCII XYZ: column mapping by option, header line or position (see xyz_io.h).

#include <pcl_ls3d/io/xyz_io.h>

#include "ascii_writers.h"
#include "local_origin.h"
#include "point_fields.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

namespace pcl_ls3d {
namespace io {

namespace {

enum class Column
{
  X,
  Y,
  Z,
  Intensity,
  Classification,
  PointSourceId,
  GpsTime,
  ReturnNumber,
  NumberOfReturns,
  Skip,
  Unknown
};

Column
columnOf(std::string name)
{
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (name == "x")
    return Column::X;
  if (name == "y")
    return Column::Y;
  if (name == "z")
    return Column::Z;
  if (name == "intensity" || name == "i")
    return Column::Intensity;
  if (name == "classification" || name == "class" || name == "label")
    return Column::Classification;
  if (name == "point_source_id" || name == "psid" || name == "source_id")
    return Column::PointSourceId;
  if (name == "gps_time" || name == "time" || name == "t")
    return Column::GpsTime;
  if (name == "return_number")
    return Column::ReturnNumber;
  if (name == "number_of_returns")
    return Column::NumberOfReturns;
  if (name == "_" || name == "skip")
    return Column::Skip;
  return Column::Unknown;
}

const char* const kColumnNames[] = {"x",
                                    "y",
                                    "z",
                                    "intensity",
                                    "classification",
                                    "point_source_id",
                                    "gps_time",
                                    "return_number",
                                    "number_of_returns"};

bool
isSeparator(char c)
{
  return c == ' ' || c == '\t' || c == ',' || c == ';' || c == '\r' || c == '\n';
}

void
tokenize(const std::string& line, std::size_t start, std::vector<std::string_view>& out)
{
  out.clear();
  std::size_t i = start;
  while (i < line.size()) {
    while (i < line.size() && isSeparator(line[i]))
      ++i;
    const std::size_t b = i;
    while (i < line.size() && !isSeparator(line[i]))
      ++i;
    if (i > b)
      out.emplace_back(line.data() + b, i - b);
  }
}

bool
parseNumber(std::string_view t, double& v)
{
  if (!t.empty() && t[0] == '+')
    t.remove_prefix(1);
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

/// Mapping from names; valid only if it names x, y and z. Unknown names are skipped.
bool
mappingFromNames(const std::vector<std::string_view>& names, std::vector<Column>& map)
{
  map.clear();
  bool has[3] = {false, false, false};
  for (const auto& n : names) {
    Column c = columnOf(std::string(n));
    if (c == Column::Unknown)
      c = Column::Skip;
    if (c <= Column::Z)
      has[static_cast<int>(c)] = true;
    map.push_back(c);
  }
  return has[0] && has[1] && has[2];
}

/// "line L, column C: cannot parse 'abc' as a number", the token quoted short (a 10 MB line of
/// garbage gives a one-line message of a hundred characters, not of 10 MB).
std::string
notANumber(const std::string& line, std::size_t line_number, std::string_view token)
{
  const std::size_t column = static_cast<std::size_t>(token.data() - line.data()) + 1;
  return "line " + std::to_string(line_number) + ", column " + std::to_string(column) + ": cannot parse " +
         detail::quote(token) + " as a number";
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

/// LoadOptions::xyz_columns as a mapping: every name known (a typo would silently skip a
/// column), x, y and z among them.
bool
mappingFromOption(const std::string& spec, std::vector<Column>& map, std::string& error)
{
  std::vector<std::string_view> tokens;
  tokenize(spec, 0, tokens);
  for (const auto& t : tokens)
    if (columnOf(std::string(t)) == Column::Unknown) {
      error = "unknown XYZ column name " + detail::quote(t);
      return false;
    }
  if (!mappingFromNames(tokens, map)) {
    error = "XYZ column list " + detail::quote(spec) + " must name x, y and z";
    return false;
  }
  return true;
}

/// The tokens of one line after a leading '#' or '//'; false when there are none.
bool
lineTokens(const std::string& line, std::vector<std::string_view>& tokens, bool& comment)
{
  std::size_t start = line.find_first_not_of(" \t\r");
  if (start == std::string::npos)
    return false;
  comment = line[start] == '#' || line.compare(start, 2, "//") == 0;
  if (comment)
    start += line[start] == '#' ? 1 : 2;
  tokenize(line, start, tokens);
  return !tokens.empty();
}

/// Before the data: a header names the columns (LoadOptions::xyz_columns, when given, wins and
/// the header is skipped); any other uncommented text is an error.
bool
readHeaderLine(const std::string& line, std::size_t line_number, const std::vector<std::string_view>& tokens,
               bool comment, bool columns_given, std::vector<Column>& map, std::string& error)
{
  std::vector<Column> candidate;
  if (mappingFromNames(tokens, candidate)) {
    if (!columns_given)
      map = candidate;
  } else if (!comment) {
    error = notANumber(line, line_number, tokens[0]);
    return false;
  }
  return true;
}

/// At the first data line: x y z by position when nothing named the columns. Returns how many
/// columns a line needs (up to the last mapped one) and fills info.fields and
/// info.xyz_unmapped_columns from the first line's column count.
std::size_t
fixColumns(std::vector<Column>& map, std::size_t columns, CloudInfo& info)
{
  if (map.empty())
    map = {Column::X, Column::Y, Column::Z};
  std::size_t mapped = 0, needed = 0;
  for (std::size_t c = 0; c < map.size() && c < columns; ++c)
    mapped += map[c] != Column::Skip;
  info.xyz_unmapped_columns = columns - mapped;
  for (std::size_t c = 0; c < map.size(); ++c)
    if (map[c] != Column::Skip)
      needed = c + 1;
  for (std::size_t c = 0; c < needed; ++c)
    if (map[c] != Column::Skip)
      info.fields.push_back(kColumnNames[static_cast<int>(map[c])]);
  return needed;
}

/// One data line into a point (attributes) and its file coordinates (appended to `xyz`).
bool
readPoint(const std::string& line, std::size_t line_number, const std::vector<std::string_view>& tokens,
          const std::vector<Column>& map, std::size_t needed, std::vector<double>& xyz,
          pcl::PointCloud<PointLiDAR>& cloud, std::string& error)
{
  if (tokens.size() < needed) {
    error = "line " + std::to_string(line_number) + ": expected at least " + std::to_string(needed) +
            " columns, found " + std::to_string(tokens.size());
    return false;
  }
  PointLiDAR p;
  double c3[3] = {0.0, 0.0, 0.0};
  for (std::size_t c = 0; c < needed; ++c) {
    if (map[c] == Column::Skip)
      continue;
    double v = 0.0;
    if (!parseNumber(tokens[c], v)) {
      error = notANumber(line, line_number, tokens[c]);
      return false;
    }
    switch (map[c]) {
    case Column::X:
      c3[0] = v;
      break;
    case Column::Y:
      c3[1] = v;
      break;
    case Column::Z:
      c3[2] = v;
      break;
    case Column::Intensity:
      p.intensity = static_cast<float>(v);
      break;
    case Column::Classification:
      p.classification = clampTo<std::uint8_t>(v);
      break;
    case Column::PointSourceId:
      p.point_source_id = clampTo<std::uint16_t>(v);
      break;
    case Column::GpsTime:
      p.gps_time = v;
      break;
    case Column::ReturnNumber:
      p.return_number = clampTo<std::uint8_t>(v);
      break;
    case Column::NumberOfReturns:
      p.number_of_returns = clampTo<std::uint8_t>(v);
      break;
    default:
      break;
    }
  }
  xyz.insert(xyz.end(), c3, c3 + 3);
  cloud.push_back(p);
  return true;
}

}  // namespace

bool
readXyz(std::istream& in, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info, std::string& error,
        const LoadOptions& options)
{
  info = CloudInfo();
  info.format = "xyz";
  cloud.clear();
  std::vector<Column> map;
  if (!options.xyz_columns.empty() && !mappingFromOption(options.xyz_columns, map, error))
    return false;
  std::vector<double> xyz;
  std::vector<std::string_view> tokens;
  std::string line;
  std::size_t line_number = 0, needed = 0;  // needed == 0: no data line yet
  while (std::getline(in, line)) {
    ++line_number;
    bool comment = false;
    if (!lineTokens(line, tokens, comment))
      continue;
    double first = 0.0;
    if (needed == 0 && (comment || !parseNumber(tokens[0], first))) {
      if (!readHeaderLine(line, line_number, tokens, comment, !options.xyz_columns.empty(), map, error))
        return false;
      continue;
    }
    if (comment)
      continue;
    if (needed == 0)
      needed = fixColumns(map, tokens.size(), info);
    if (!readPoint(line, line_number, tokens, map, needed, xyz, cloud, error))
      return false;
  }
  if (in.bad()) {
    error = "read error";
    return false;
  }
  return detail::applyLocalOrigin(xyz, cloud, info, options, error);
}

bool
writeXyzFile(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
             std::string& error, const SaveOptions& options)
{
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) {
    error = "cannot open the file for writing";
    return false;
  }
  bool ok = std::fputs("# x y z intensity classification point_source_id gps_time return_number "
                       "number_of_returns\n",
                       f) >= 0;
  std::string line;
  for (std::size_t i = 0; ok && i < cloud.size(); ++i) {
    const PointLiDAR& p = cloud[i];
    line.clear();
    for (int k = 0; k < 3; ++k) {  // x_file = x_local + origin in double
      detail::appendNumber(line, static_cast<double>(p.data[k]) + origin[k], options.xyz_decimals);
      line += ' ';
    }
    detail::appendNumber(line, p.intensity);
    line += ' ' + std::to_string(p.classification) + ' ' + std::to_string(p.point_source_id) + ' ';
    detail::appendNumber(line, p.gps_time);
    line += ' ' + std::to_string(p.return_number) + ' ' + std::to_string(p.number_of_returns) + '\n';
    ok = std::fwrite(line.data(), 1, line.size(), f) == line.size();
  }
  ok = (std::fclose(f) == 0) && ok;
  if (!ok)
    error = "write error";
  return ok;
}

}  // namespace io
}  // namespace pcl_ls3d
