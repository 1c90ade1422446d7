#pragma once
/// \file header_comments.h
/// \brief The CRS comment line of PCD ("# pcl_ls3d crs WKT") and PLY ("comment pcl_ls3d crs
///        WKT") headers: written on one line, read back from the first such line.

#include <algorithm>
#include <string>
#include <string_view>

namespace pcl_ls3d {
namespace io {
namespace detail {

/// \a prefix + \a text on one line (line breaks of the text made spaces), without a newline.
inline std::string
oneLineComment(std::string_view prefix, const std::string& text)
{
  std::string line = std::string(prefix) + text;
  std::replace_if(
      line.begin(), line.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  return line;
}

/// The line without trailing carriage returns and spaces.
inline std::string_view
withoutLineEnd(std::string_view line)
{
  while (!line.empty() && (line.back() == '\r' || line.back() == ' '))
    line.remove_suffix(1);
  return line;
}

/// Sets \a value to what follows \a prefix on \a line (withoutLineEnd()) unless \a value is
/// set already: the first such line counts.
inline void
firstCommentValue(std::string_view line, std::string_view prefix, std::string& value)
{
  if (value.empty() && line.substr(0, prefix.size()) == prefix)
    value = std::string(withoutLineEnd(line.substr(prefix.size())));
}

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
