#include "colour_bar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pcl_ls3d {
namespace maps {
namespace detail {

namespace {

// The ramp's stops as offsets from the top (max) to the bottom (min).
std::vector<std::pair<double, Rgb>>
gradientStops(const ColourMap& c)
{
  std::vector<std::pair<double, Rgb>> stops;
  const std::vector<ColourMap::Stop>& s = c.stops();
  for (auto it = s.rbegin(); it != s.rend(); ++it)
    stops.emplace_back((c.max() - it->value) / (c.max() - c.min()), it->colour);
  return stops;
}

std::string
clampedLabel(const ColourMap& c, const MapStyle& style, std::size_t k)
{
  const std::vector<double>& ticks = c.ticks();
  std::string label = tickLabel(style.tick_format.c_str(), ticks[k]);
  if (style.clamp_labels && k == 0 && ticks[k] <= c.min())
    label = "\u2264 " + label;
  if (style.clamp_labels && k + 1 == ticks.size() && ticks[k] >= c.max())
    label = "\u2265 " + label;
  return label;
}

}  // namespace

std::string
tickLabel(const char* format, double value)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, value);
  std::string s = buf;
  if (s.find_first_of("123456789") == std::string::npos && !s.empty() && (s[0] == '+' || s[0] == '-'))
    s = s.substr(1);  // zero has no sign
  // A typographic minus reads better than a hyphen in a legend.
  if (!s.empty() && s[0] == '-')
    s = "\u2212" + s.substr(1);
  return s;
}

int
colourBarWidth(const ColourMap& colours, const MapStyle& style)
{
  double w = kBarWidth;
  for (std::size_t k = 0; k < colours.ticks().size(); ++k)
    w = std::max(w, kBarWidth + 8 + Drawing::textWidth(clampedLabel(colours, style, k)));
  return static_cast<int>(std::ceil(w));
}

void
drawColourBar(Drawing& d, int x0, int y0, int h, const ColourMap& c, const MapStyle& style)
{
  // Rows of pixels: a value's line is the pixel row it falls in, as the ramp shows it.
  auto yOf = [&](double v) {
    return y0 + static_cast<int>(std::lround((c.max() - v) / (c.max() - c.min()) * (h - 1)));
  };
  d.verticalGradient(x0, y0, kBarWidth, h, gradientStops(c));
  d.frame(x0 - 1, y0 - 1, kBarWidth + 2, h + 2, kFrame);
  for (double s : c.steps())
    d.fillRect(x0, yOf(s), kBarWidth, 1, kInk);
  const int ascent = Drawing::ascent();
  for (std::size_t k = 0; k < c.ticks().size(); ++k) {
    const int y = yOf(c.ticks()[k]);
    d.fillRect(x0 + kBarWidth, y, 5, 1, kInk);
    d.text(x0 + kBarWidth + 8, y + ascent / 2 - 1, clampedLabel(c, style, k), kInk);
  }
}

}  // namespace detail
}  // namespace maps
}  // namespace pcl_ls3d
