#pragma once
/// \file image.h
/// \brief An 8-bit RGB image with the few drawing operations maps need: rectangles, lines and
///        anti-aliased text (DejaVu Sans glyphs compiled into the library, UTF-8 input).

#include <pcl_ls3d/maps/colour_map.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace maps {

enum class FontStyle { REGULAR, BOLD };
enum class TextAlign { LEFT, CENTRE, RIGHT };

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

  Rgb
  get(int x, int y) const;
  /// Sets a pixel; outside the image nothing happens.
  void
  set(int x, int y, Rgb c);
  /// Mixes c over the pixel with opacity alpha ∈ [0, 1].
  void
  blend(int x, int y, Rgb c, double alpha);
  void
  fillRect(int x, int y, int w, int h, Rgb c);
  /// One-pixel outline.
  void
  drawRect(int x, int y, int w, int h, Rgb c);
  void
  drawLine(int x0, int y0, int x1, int y1, Rgb c);

  /// Draws UTF-8 text with its baseline at y; returns the advance in pixels. Characters
  /// without a glyph are drawn as '?'.
  int
  drawText(int x, int y, const std::string& text, Rgb c, FontStyle style = FontStyle::REGULAR,
           TextAlign align = TextAlign::LEFT);
  /// Advance width of a text in pixels.
  static int
  textWidth(const std::string& text, FontStyle style = FontStyle::REGULAR);
  /// Line height and ascent of a font in pixels.
  static int
  lineHeight(FontStyle style = FontStyle::REGULAR);
  static int
  ascent(FontStyle style = FontStyle::REGULAR);

private:
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> rgb_;
};

}  // namespace maps
}  // namespace pcl_ls3d
