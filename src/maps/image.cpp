#include <pcl_ls3d/maps/image.h>

#include "font_atlas.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace pcl_ls3d {
namespace maps {

namespace {

const detail::FontData&
font(FontStyle style)
{
  return style == FontStyle::BOLD ? detail::kBold : detail::kRegular;
}

// Decodes one UTF-8 character at text[i] and advances i (invalid bytes give '?').
unsigned
nextCodePoint(const std::string& text, std::size_t& i)
{
  const unsigned char c = static_cast<unsigned char>(text[i++]);
  int extra = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : -1;
  if (extra < 0)
    return '?';
  unsigned cp = extra == 0 ? c : (c & (0x3Fu >> extra));
  for (; extra > 0; --extra) {
    if (i >= text.size() || (static_cast<unsigned char>(text[i]) >> 6) != 2)
      return '?';
    cp = (cp << 6) | (static_cast<unsigned char>(text[i++]) & 0x3Fu);
  }
  return cp;
}

const detail::Glyph*
findGlyph(const detail::FontData& f, unsigned code)
{
  const detail::Glyph* end = f.glyphs + f.count;
  const detail::Glyph* g = std::lower_bound(
      f.glyphs, end, code, [](const detail::Glyph& a, unsigned c) { return a.code < c; });
  if (g != end && g->code == code)
    return g;
  return code == '?' ? nullptr : findGlyph(f, '?');
}

int
hexValue(char c)
{
  return c <= '9' ? c - '0' : c - 'a' + 10;
}

}  // namespace

Image::Image(int width, int height, Rgb background)
: width_(std::max(0, width)), height_(std::max(0, height))
, rgb_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 3)
{
  fillRect(0, 0, width_, height_, background);
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

void
Image::blend(int x, int y, Rgb c, double alpha)
{
  if (alpha <= 0.0)
    return;
  const Rgb o = get(x, y);
  auto mix = [alpha](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(a + (static_cast<double>(b) - a) * std::min(1.0, alpha)));
  };
  set(x, y, {mix(o.r, c.r), mix(o.g, c.g), mix(o.b, c.b)});
}

void
Image::fillRect(int x, int y, int w, int h, Rgb c)
{
  for (int yy = std::max(0, y); yy < std::min(height_, y + h); ++yy)
    for (int xx = std::max(0, x); xx < std::min(width_, x + w); ++xx)
      set(xx, yy, c);
}

void
Image::drawRect(int x, int y, int w, int h, Rgb c)
{
  drawLine(x, y, x + w - 1, y, c);
  drawLine(x, y + h - 1, x + w - 1, y + h - 1, c);
  drawLine(x, y, x, y + h - 1, c);
  drawLine(x + w - 1, y, x + w - 1, y + h - 1, c);
}

void
Image::drawLine(int x0, int y0, int x1, int y1, Rgb c)
{
  // Bresenham.
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  for (;;) {
    set(x0, y0, c);
    if (x0 == x1 && y0 == y1)
      break;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

int
Image::textWidth(const std::string& text, FontStyle style)
{
  const detail::FontData& f = font(style);
  int w = 0;
  for (std::size_t i = 0; i < text.size();)
    if (const detail::Glyph* g = findGlyph(f, nextCodePoint(text, i)))
      w += g->advance;
  return w;
}

int
Image::lineHeight(FontStyle style)
{
  return static_cast<int>(font(style).height);
}

int
Image::ascent(FontStyle style)
{
  return static_cast<int>(font(style).ascender);
}

int
Image::drawText(int x, int y, const std::string& text, Rgb c, FontStyle style, TextAlign align)
{
  const detail::FontData& f = font(style);
  const int w = textWidth(text, style);
  int pen = align == TextAlign::LEFT ? x : align == TextAlign::CENTRE ? x - w / 2 : x - w;
  for (std::size_t i = 0; i < text.size();) {
    const detail::Glyph* g = findGlyph(f, nextCodePoint(text, i));
    if (!g)
      continue;
    for (int r = 0; r < g->rows; ++r)
      for (int col = 0; col < g->width; ++col) {
        const int v = hexValue(f.coverage[g->offset + static_cast<std::size_t>(r * g->width + col)]);
        blend(pen + g->left + col, y - g->top + r, c, v / 15.0);
      }
    pen += g->advance;
  }
  return w;
}

}  // namespace maps
}  // namespace pcl_ls3d
