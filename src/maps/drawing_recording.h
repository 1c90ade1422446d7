#pragma once
// Private: the cairo recording behind a Drawing, shared by what draws on it (drawing.cpp) and
// what writes it out (drawing_output.cpp).
#include <pcl_ls3d/maps/drawing.h>

#include <cairo.h>

namespace pcl_ls3d {
namespace maps {

struct Drawing::Recording
{
  cairo_surface_t* surface = nullptr;
  cairo_t* cr = nullptr;

  Recording(int width, int height)
  {
    const cairo_rectangle_t extents{0.0, 0.0, static_cast<double>(width), static_cast<double>(height)};
    surface = cairo_recording_surface_create(CAIRO_CONTENT_COLOR_ALPHA, &extents);
    cr = cairo_create(surface);
  }
  ~Recording()
  {
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
  }
  Recording(const Recording&) = delete;
  Recording&
  operator=(const Recording&) = delete;
};

}  // namespace maps
}  // namespace pcl_ls3d
