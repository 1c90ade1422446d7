#include <pcl_ls3d/maps/map_format.h>

namespace pcl_ls3d {
namespace maps {

bool
parseMapFormat(const std::string& text, MapFormat& format)
{
  for (MapFormat f : {MapFormat::PNG, MapFormat::PDF, MapFormat::SVG})
    if (text == mapFormatName(f)) {
      format = f;
      return true;
    }
  return false;
}

std::string
mapFormatName(MapFormat format)
{
  switch (format) {
  case MapFormat::PDF:
    return "pdf";
  case MapFormat::SVG:
    return "svg";
  default:
    return "png";
  }
}

std::string
mapExtension(MapFormat format)
{
  return "." + mapFormatName(format);
}

}  // namespace maps
}  // namespace pcl_ls3d
