#pragma once
// Private: the colour bar beside a raster map and the labels of its ticks.
#include <pcl_ls3d/maps/drawing.h>
#include <pcl_ls3d/maps/map_rendering.h>

#include <string>

namespace pcl_ls3d {
namespace maps {
namespace detail {

constexpr int kBarWidth = 20;
constexpr Rgb kInk{30, 30, 30}, kFrame{90, 90, 90};

/// printf of one number, zero without a sign and a typographic minus.
std::string
tickLabel(const char* format, double value);

/// Width of the colour bar with its tick labels.
int
colourBarWidth(const ColourMap& colours, const MapStyle& style);

/// The bar from max (top) to min (bottom) at (x, y), \a height high: the ramp, its class
/// boundaries as lines, ticks with labels to its right ("≤ min" and "≥ max" with clamp_labels).
void
drawColourBar(Drawing& drawing, int x, int y, int height, const ColourMap& colours, const MapStyle& style);

}  // namespace detail
}  // namespace maps
}  // namespace pcl_ls3d
