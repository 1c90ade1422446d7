#pragma once
// Private: an Image as a cairo image surface and back (cairo keeps 32-bit pixels, xRGB).
#include <pcl_ls3d/maps/image.h>

#include <cairo.h>

namespace pcl_ls3d {
namespace maps {
namespace detail {

/// A new opaque (RGB24) surface holding \a image's pixels; the caller destroys it. Check
/// cairo_surface_status() (a huge image may not be allocated).
cairo_surface_t*
surfaceOf(const Image& image);

/// The pixels of an image surface (RGB24 or ARGB32: colours un-premultiplied, alpha dropped).
Image
imageOf(cairo_surface_t* surface);

}  // namespace detail
}  // namespace maps
}  // namespace pcl_ls3d
