#include "cairo_image.h"

#include <cstdint>
#include <cstring>

namespace pcl_ls3d {
namespace maps {
namespace detail {

cairo_surface_t*
surfaceOf(const Image& image)
{
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, image.width(), image.height());
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS)
    return surface;
  cairo_surface_flush(surface);
  unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const std::uint8_t* rgb = image.pixels().data();
  for (int y = 0; y < image.height(); ++y) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
    for (int x = 0; x < image.width(); ++x, rgb += 3)
      row[x] = 0xff000000u | std::uint32_t{rgb[0]} << 16 | std::uint32_t{rgb[1]} << 8 | rgb[2];
  }
  cairo_surface_mark_dirty(surface);
  return surface;
}

Image
imageOf(cairo_surface_t* surface)
{
  cairo_surface_flush(surface);
  const int w = cairo_image_surface_get_width(surface), h = cairo_image_surface_get_height(surface);
  const bool alpha = cairo_image_surface_get_format(surface) == CAIRO_FORMAT_ARGB32;
  const unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  Image image(w, h);
  if (!data)
    return Image();
  std::uint8_t* rgb = image.pixels().data();
  for (int y = 0; y < h; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
    for (int x = 0; x < w; ++x, rgb += 3) {
      const std::uint32_t p = row[x];
      const std::uint32_t a = alpha ? p >> 24 : 255u;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t c = (p >> (16 - 8 * k)) & 0xffu;
        rgb[k] = static_cast<std::uint8_t>(a == 0 ? 0 : a == 255 ? c : (c * 255 + a / 2) / a);
      }
    }
  }
  return image;
}

}  // namespace detail
}  // namespace maps
}  // namespace pcl_ls3d
