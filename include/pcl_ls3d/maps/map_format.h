#pragma once
/// \file map_format.h
/// \brief The file formats maps are written in: PNG (pixels, for screens and web pages), PDF and
///        SVG (vectors with real text, for reports); the tools' `-map_format` option.

#include <string>

namespace pcl_ls3d {
namespace maps {

enum class MapFormat
{
  PNG,
  PDF,
  SVG
};

/// "png", "pdf" or "svg" (lower case, as the option is written) into \a format; false otherwise.
bool
parseMapFormat(const std::string& text, MapFormat& format);

/// "png", "pdf" or "svg".
std::string
mapFormatName(MapFormat format);

/// The file name extension with its dot: ".png", ".pdf" or ".svg".
std::string
mapExtension(MapFormat format);

}  // namespace maps
}  // namespace pcl_ls3d
