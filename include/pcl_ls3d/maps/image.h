#pragma once
/// \file image.h
/// \brief An 8-bit RGB pixel image: the picture a Drawing embeds (a raster drawn pixel by pixel)
///        and what a rasterised Drawing or a PNG file reads back as.

#include <pcl_ls3d/maps/colour_map.h>

#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace maps {

/// \brief Row-major RGB pixels, (0, 0) top left.
class Image
{
public:
  Image() = default;
  Image(int width, int height, Rgb background = {255, 255, 255});

  int
  width() const
  {
    return width_;
  }
  int
  height() const
  {
    return height_;
  }
  bool
  empty() const
  {
    return width_ <= 0 || height_ <= 0;
  }
  /// Three bytes per pixel, rows from the top.
  const std::vector<std::uint8_t>&
  pixels() const
  {
    return rgb_;
  }
  std::vector<std::uint8_t>&
  pixels()
  {
    return rgb_;
  }

  /// The pixel's colour; black outside the image.
  Rgb
  get(int x, int y) const;
  /// Sets a pixel; outside the image nothing happens.
  void
  set(int x, int y, Rgb c);

private:
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> rgb_;
};

}  // namespace maps
}  // namespace pcl_ls3d
