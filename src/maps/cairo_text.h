#pragma once
// Private: text through cairo's toy font API (fontconfig and FreeType underneath), set up the
// same way wherever a Drawing is measured or drawn so that widths agree in every format.
#include <pcl_ls3d/maps/drawing.h>

#include <cairo.h>

#include <string>

namespace pcl_ls3d {
namespace maps {
namespace detail {

/// Selects DejaVu Sans (12 px regular, 14 px bold) on \a cr with unhinted metrics.
void
selectFont(cairo_t* cr, FontStyle style);

/// \a text with every byte that does not start a valid UTF-8 character replaced by '?':
/// cairo refuses invalid UTF-8 and would stop drawing altogether.
std::string
validUtf8(const std::string& text);

}  // namespace detail
}  // namespace maps
}  // namespace pcl_ls3d
