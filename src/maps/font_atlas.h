#pragma once
// Private: the glyph bitmaps generated into font_atlas.cpp (scripts/maps/make_font_atlas.cpp).
#include <cstddef>

namespace pcl_ls3d {
namespace maps {
namespace detail {

struct Glyph
{
  unsigned code;        // Unicode code point
  int width, rows;      // bitmap size
  int left, top;        // bitmap offset from the pen position (top: above the baseline)
  int advance;          // pen advance
  std::size_t offset;   // first pixel in the coverage string
};

struct FontData
{
  const Glyph* glyphs;  // sorted by code
  std::size_t count;
  const char* coverage; // one hex digit (0–f) per pixel, row-major per glyph
  long ascender, height;
};

extern const FontData kRegular;
extern const FontData kBold;

}  // namespace detail
}  // namespace maps
}  // namespace pcl_ls3d
