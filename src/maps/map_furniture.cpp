// The furniture every map carries: a scale bar and a north arrow; and the round steps both
// scale bars and axes use.
#include <pcl_ls3d/maps/map_rendering.h>

#include "colour_bar.h"

#include <cmath>
#include <cstdio>

namespace pcl_ls3d {
namespace maps {

using detail::kInk;

ScaleBar
drawScaleBar(Drawing& d, int x0, int y0, int map_w, double ground_per_pixel, const std::string& unit)
{
  const double len = niceStep(map_w * ground_per_pixel, 4);
  const int px = static_cast<int>(std::lround(len / ground_per_pixel));
  if (px < 8)
    return {};
  for (int k = 0; k < 4; ++k) {
    const int a = x0 + k * px / 4, b = x0 + (k + 1) * px / 4;
    d.fillRect(a, y0, b - a, 6, k % 2 ? Rgb{255, 255, 255} : kInk);
  }
  d.frame(x0, y0, px, 6, kInk);
  const int base = y0 + 8 + Drawing::ascent();
  d.text(x0, base, "0", kInk, FontStyle::REGULAR, TextAlign::CENTRE);
  char label[64];
  std::snprintf(label, sizeof(label), "%g %s", len, unit.c_str());
  d.text(x0 + px, base, label, kInk, FontStyle::REGULAR, TextAlign::CENTRE);
  return {len, px};
}

void
drawNorthArrow(Drawing& d, int cx, int top)
{
  const double x = cx + 0.5;  // the middle of pixel column cx
  const double head = top + 14.0, shoulder = top + 24.0, foot = top + 36.0;
  d.fillPolygon({{x, head},
                 {x + 5.0, shoulder},
                 {x + 2.5, shoulder},
                 {x + 2.5, foot},
                 {x - 2.5, foot},
                 {x - 2.5, shoulder},
                 {x - 5.0, shoulder}},
                kInk);
  d.text(x, top + 12, "N", kInk, FontStyle::BOLD, TextAlign::CENTRE);
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
