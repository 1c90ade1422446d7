#include <pcl_ls3d/maps/image.h>

#include <algorithm>

namespace pcl_ls3d {
namespace maps {

Image::Image(int width, int height, Rgb background)
    : width_(std::max(0, width)), height_(std::max(0, height)),
      rgb_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 3)
{
  for (std::size_t k = 0; k < rgb_.size(); k += 3) {
    rgb_[k] = background.r;
    rgb_[k + 1] = background.g;
    rgb_[k + 2] = background.b;
  }
}

Rgb
Image::get(int x, int y) const
{
  if (x < 0 || y < 0 || x >= width_ || y >= height_)
    return {};
  const std::size_t k = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + x) * 3;
  return {rgb_[k], rgb_[k + 1], rgb_[k + 2]};
}

void
Image::set(int x, int y, Rgb c)
{
  if (x < 0 || y < 0 || x >= width_ || y >= height_)
    return;
  const std::size_t k = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + x) * 3;
  rgb_[k] = c.r;
  rgb_[k + 1] = c.g;
  rgb_[k + 2] = c.b;
}

}  // namespace maps
}  // namespace pcl_ls3d
