// Raster map layout: title block, map with frame (and outlined cells), north arrow, colour bar
// with ticks and class boundaries, legend, scale bar and footer.
#include <pcl_ls3d/maps/map_rendering.h>

#include "colour_bar.h"
#include "raster_picture.h"

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {
namespace maps {

namespace {

using detail::kBarWidth;
using detail::kFrame;
using detail::kInk;

constexpr int kMargin = 16, kGap = 24;

// Where everything goes, in pixels.
struct Layout
{
  double scale = 1.0;  // pixels per cell (≥ 1: whole enlargement; < 1: cells averaged)
  int map_x = kMargin, map_y = 0, map_w = 0, map_h = 0;
  int side_x = 0, bar_h = 0, side_h = 0;
  int width = 0, height = 0;
};

double
mapScale(const GridGeometry& g, const MapStyle& style)
{
  const double s =
      std::min(static_cast<double>(style.max_width) / g.cols, static_cast<double>(style.max_height) / g.rows);
  return s >= 1.0 ? std::floor(s) : s;
}

int
textWidth(const std::string& text, FontStyle style = FontStyle::REGULAR)
{
  return static_cast<int>(std::ceil(Drawing::textWidth(text, style)));
}

int
sidePanelWidth(const MapStyle& style, const ColourMap& c)
{
  int w = std::max(detail::colourBarWidth(c, style), kBarWidth + 8 + textWidth(style.unit, FontStyle::BOLD));
  w = std::max(w, 20 + textWidth("no data"));
  for (const std::string& line : style.legend)
    w = std::max(w, textWidth(line) + 20);
  return w;
}

Layout
layoutOf(const Raster& raster, const ColourMap& colours, const MapStyle& style)
{
  Layout l;
  l.scale = mapScale(raster.grid, style);
  l.map_w = std::max(1, static_cast<int>(raster.grid.cols * l.scale));
  l.map_h = std::max(1, static_cast<int>(raster.grid.rows * l.scale));
  const int line = Drawing::lineHeight();
  l.map_y = kMargin + (style.title.empty() ? 0 : Drawing::lineHeight(FontStyle::BOLD)) +
            static_cast<int>(style.subtitle.size()) * line + 8;
  l.side_x = l.map_x + l.map_w + kGap;
  l.width = l.side_x + sidePanelWidth(style, colours) + kMargin;
  for (const std::string& s : style.subtitle)
    l.width = std::max(l.width, 2 * kMargin + textWidth(s));
  l.width = std::max(l.width, 2 * kMargin + textWidth(style.title, FontStyle::BOLD));
  l.width = std::max(l.width, 2 * kMargin + textWidth(style.footer));
  l.bar_h = std::max(160, std::min(l.map_h, 320));
  l.side_h = 40 + l.bar_h + 16 + static_cast<int>(style.legend.size() + 1) * line;
  const int below = (style.length_unit.empty() ? 0 : 30) + (style.footer.empty() ? 0 : line) + kMargin;
  l.height = l.map_y + std::max(l.map_h, l.side_h) + 8 + below;
  return l;
}

void
drawHead(Drawing& d, const MapStyle& style)
{
  int y = kMargin;
  if (!style.title.empty()) {
    d.text(kMargin, y + Drawing::ascent(FontStyle::BOLD), style.title, kInk, FontStyle::BOLD);
    y += Drawing::lineHeight(FontStyle::BOLD);
  }
  for (const std::string& s : style.subtitle) {
    d.text(kMargin, y + Drawing::ascent(), s, kInk);
    y += Drawing::lineHeight();
  }
}

void
drawMapArea(Drawing& d, const Layout& l, const Raster& raster, const ColourMap& colours,
            const MapStyle& style, const Raster* outline)
{
  const Image cells = detail::cellPixels(raster, l.scale, colours, style.no_data);
  d.image(cells, l.map_x, l.map_y);
  if (outline && outline->grid.cols == raster.grid.cols && outline->grid.rows == raster.grid.rows) {
    // Two pixels on large cells; one on small cells, which a wider line would hide.
    const double width = l.scale >= 8.0 ? 2.0 : 1.0;
    d.lines(detail::outlineSegments(*outline, l.scale, l.map_x, l.map_y, width / 2.0), kOutlineColour, width,
            false);
  }
  d.frame(l.map_x - 1, l.map_y - 1, l.map_w + 2, l.map_h + 2, kFrame);
}

// North arrow, unit, colour bar, no-data swatch and legend lines.
void
drawSidePanel(Drawing& d, const Layout& l, const ColourMap& colours, const MapStyle& style)
{
  const int sx = l.side_x;
  drawNorthArrow(d, sx + kBarWidth / 2, l.map_y);
  d.text(sx + kBarWidth + 8, l.map_y + 30, style.unit, kInk, FontStyle::BOLD);
  const int bar_y = l.map_y + 40;
  detail::drawColourBar(d, sx, bar_y, l.bar_h, colours, style);
  int ly = bar_y + l.bar_h + 16;
  d.fillRect(sx, ly, 14, 10, style.no_data);
  d.frame(sx, ly, 14, 10, kFrame);
  d.text(sx + 20, ly + 9, "no data", kInk);
  for (const std::string& line : style.legend) {
    ly += Drawing::lineHeight();
    d.text(sx, ly + 9, line, kInk);
  }
}

}  // namespace

Drawing
renderRasterMap(const Raster& raster, const ColourMap& colours, const MapStyle& style, const Raster* outline)
{
  if (!raster.grid.valid() || !colours.valid())
    return Drawing();
  const Layout l = layoutOf(raster, colours, style);
  Drawing d(l.width, l.height);
  d.setTitle(style.title);
  drawHead(d, style);
  drawMapArea(d, l, raster, colours, style, outline);
  drawSidePanel(d, l, colours, style);
  int by = l.map_y + std::max(l.map_h, l.side_h) + 8;
  if (!style.length_unit.empty()) {
    drawScaleBar(d, l.map_x, by, l.map_w, raster.grid.cell / l.scale, style.length_unit);
    by += 30;
  }
  if (!style.footer.empty())
    d.text(kMargin, by + Drawing::ascent(), style.footer, kFrame);
  return d;
}

}  // namespace maps
}  // namespace pcl_ls3d
