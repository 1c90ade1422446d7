// Raster map layout: title block, map with frame, scale bar and north arrow, colour bar with
// ticks and class boundaries, legend, footer.
#include <pcl_ls3d/maps/map_rendering.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pcl_ls3d {
namespace maps {

namespace {

constexpr int kMargin = 16, kGap = 24, kBarWidth = 20;
const Rgb kInk{30, 30, 30}, kFrame{90, 90, 90}, kWhite{255, 255, 255};

std::string
format(const char* fmt, double v)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), fmt, v);
  std::string s = buf;
  if (s.find_first_of("123456789") == std::string::npos && !s.empty() && (s[0] == '+' || s[0] == '-'))
    s = s.substr(1);  // zero has no sign
  // A typographic minus reads better than a hyphen in a legend.
  if (!s.empty() && s[0] == '-')
    s = "\u2212" + s.substr(1);
  return s;
}

// Pixels per cell (≥ 1: whole enlargement; < 1: cells averaged into pixels).
double
mapScale(const GridGeometry& g, const MapStyle& style)
{
  const double s = std::min(static_cast<double>(style.max_width) / g.cols,
                            static_cast<double>(style.max_height) / g.rows);
  return s >= 1.0 ? std::floor(s) : s;
}

// Mean of the finite cells under pixel (px, py).
float
sampleCells(const Raster& r, double scale, int px, int py)
{
  const int c0 = static_cast<int>(px / scale), r0 = static_cast<int>(py / scale);
  const int c1 = std::max(c0 + 1, std::min(r.grid.cols, static_cast<int>((px + 1) / scale)));
  const int r1 = std::max(r0 + 1, std::min(r.grid.rows, static_cast<int>((py + 1) / scale)));
  double sum = 0.0;
  int n = 0;
  for (int y = r0; y < std::min(r1, r.grid.rows); ++y)
    for (int x = c0; x < std::min(c1, r.grid.cols); ++x)
      if (std::isfinite(r.at(x, y))) {
        sum += r.at(x, y);
        ++n;
      }
  return n ? static_cast<float>(sum / n) : std::numeric_limits<float>::quiet_NaN();
}

void
drawMap(Image& img, int x0, int y0, int w, int h, const Raster& r, double scale,
        const ColourMap& colours, Rgb no_data)
{
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const float v = sampleCells(r, scale, px, py);
      img.set(x0 + px, y0 + py, std::isfinite(v) ? colours.colour(v) : no_data);
    }
  img.drawRect(x0 - 1, y0 - 1, w + 2, h + 2, kFrame);
}

// Vertical bar from max (top) to min (bottom) with tick labels to its right; returns its width.
int
drawColourBar(Image& img, int x0, int y0, int h, const ColourMap& c, const MapStyle& style)
{
  auto yOf = [&](double v) { return y0 + static_cast<int>(std::lround((c.max() - v) / (c.max() - c.min()) * (h - 1))); };
  for (int y = 0; y < h; ++y)
    img.fillRect(x0, y0 + y, kBarWidth, 1, c.colour(c.max() - (c.max() - c.min()) * (y + 0.5) / h));
  img.drawRect(x0 - 1, y0 - 1, kBarWidth + 2, h + 2, kFrame);
  for (double s : c.steps())
    img.drawLine(x0, yOf(s), x0 + kBarWidth - 1, yOf(s), kInk);
  int width = kBarWidth;
  const std::vector<double>& ticks = c.ticks();
  for (std::size_t k = 0; k < ticks.size(); ++k) {
    const int y = yOf(ticks[k]);
    img.drawLine(x0 + kBarWidth, y, x0 + kBarWidth + 4, y, kInk);
    std::string label = format(style.tick_format.c_str(), ticks[k]);
    if (style.clamp_labels && k == 0 && ticks[k] <= c.min())
      label = "\u2264 " + label;
    if (style.clamp_labels && k + 1 == ticks.size() && ticks[k] >= c.max())
      label = "\u2265 " + label;
    width = std::max(width, kBarWidth + 8 + img.drawText(x0 + kBarWidth + 8, y + Image::ascent() / 2 - 1, label, kInk));
  }
  return width;
}

int
legendWidth(const MapStyle& style, const ColourMap& c)
{
  int w = kBarWidth + 8 + Image::textWidth("\u2265 " + format(style.tick_format.c_str(), c.max()));
  w = std::max(w, Image::textWidth(style.unit, FontStyle::BOLD));
  for (const std::string& line : style.legend)
    w = std::max(w, Image::textWidth(line) + 20);
  return w;
}

}  // namespace

Image
renderRasterMap(const Raster& raster, const ColourMap& colours, const MapStyle& style)
{
  if (!raster.grid.valid() || !colours.valid())
    return Image();
  const double scale = mapScale(raster.grid, style);
  const int map_w = std::max(1, static_cast<int>(raster.grid.cols * scale));
  const int map_h = std::max(1, static_cast<int>(raster.grid.rows * scale));
  const int line = Image::lineHeight(), title_line = Image::lineHeight(FontStyle::BOLD);
  const int head = kMargin + (style.title.empty() ? 0 : title_line) +
                   static_cast<int>(style.subtitle.size()) * line + 8;
  const int side = legendWidth(style, colours);
  int width = kMargin + map_w + kGap + side + kMargin;
  for (const std::string& s : style.subtitle)
    width = std::max(width, 2 * kMargin + Image::textWidth(s));
  width = std::max(width, 2 * kMargin + Image::textWidth(style.title, FontStyle::BOLD));
  width = std::max(width, 2 * kMargin + Image::textWidth(style.footer));
  const int bar_h = std::max(160, std::min(map_h, 320));
  const int side_h = 40 + bar_h + 16 + static_cast<int>(style.legend.size() + 1) * line;
  const int below = (style.length_unit.empty() ? 0 : 30) + (style.footer.empty() ? 0 : line) + kMargin;
  Image img(width, head + std::max(map_h, side_h) + 8 + below);

  int y = kMargin;
  if (!style.title.empty()) {
    img.drawText(kMargin, y + Image::ascent(FontStyle::BOLD), style.title, kInk, FontStyle::BOLD);
    y += title_line;
  }
  for (const std::string& s : style.subtitle) {
    img.drawText(kMargin, y + Image::ascent(), s, kInk);
    y += line;
  }
  const int map_x = kMargin, map_y = head;
  drawMap(img, map_x, map_y, map_w, map_h, raster, scale, colours, style.no_data);

  // Side panel: north arrow, unit, colour bar, legend (with the no-data swatch).
  const int sx = map_x + map_w + kGap;
  drawNorthArrow(img, sx + kBarWidth / 2, map_y);
  img.drawText(sx + kBarWidth + 8, map_y + 30, style.unit, kInk, FontStyle::BOLD);
  const int bar_y = map_y + 40;
  drawColourBar(img, sx, bar_y, bar_h, colours, style);
  int ly = bar_y + bar_h + 16;
  img.fillRect(sx, ly, 14, 10, style.no_data);
  img.drawRect(sx, ly, 14, 10, kFrame);
  img.drawText(sx + 20, ly + 9, "no data", kInk);
  for (const std::string& l : style.legend) {
    ly += line;
    img.drawText(sx, ly + 9, l, kInk);
  }

  int by = map_y + std::max(map_h, side_h) + 8;
  if (!style.length_unit.empty()) {
    drawScaleBar(img, map_x, by, map_w, raster.grid.cell / scale, style.length_unit);
    by += 30;
  }
  if (!style.footer.empty())
    img.drawText(kMargin, by + Image::ascent(), style.footer, {90, 90, 90});
  return img;
}

ScaleBar
drawScaleBar(Image& img, int x0, int y0, int map_w, double ground_per_pixel, const std::string& unit)
{
  const double target = map_w * ground_per_pixel / 4.0;
  const double len = niceStep(target * 4.0, 4);
  const int px = static_cast<int>(std::lround(len / ground_per_pixel));
  if (px < 8)
    return {};
  for (int k = 0; k < 4; ++k) {
    const int a = x0 + k * px / 4, b = x0 + (k + 1) * px / 4;
    img.fillRect(a, y0, b - a, 6, k % 2 ? kWhite : kInk);
  }
  img.drawRect(x0, y0, px, 6, kInk);
  const int base = y0 + 8 + Image::ascent();
  img.drawText(x0, base, "0", kInk, FontStyle::REGULAR, TextAlign::CENTRE);
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g %s", len, unit.c_str());
  img.drawText(x0 + px, base, buf, kInk, FontStyle::REGULAR, TextAlign::CENTRE);
  return {len, px};
}

void
drawNorthArrow(Image& img, int cx, int top)
{
  const int h = 22;
  for (int y = 0; y < h; ++y) {
    const int half = y < 10 ? y / 2 : 2;
    img.drawLine(cx - half, top + 14 + y, cx + half, top + 14 + y, kInk);
  }
  img.drawText(cx, top + 12, "N", kInk, FontStyle::BOLD, TextAlign::CENTRE);
}

double
niceStep(double range, int count)
{
  if (!(range > 0.0) || count < 1)
    return 1.0;
  const double raw = range / count;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / p;
  return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * p;
}

}  // namespace maps
}  // namespace pcl_ls3d
