#pragma once
/// \file map_rendering.h
/// \brief Maps and charts a client can read without the software: a raster in colour with a
///        title, a colour bar with labelled ticks and class boundaries, a legend, a scale bar and
///        a north arrow; and overlaid histograms (e.g. discrepancies before / after). Each is a
///        Drawing, written as PNG, PDF or SVG.

#include <pcl_ls3d/maps/colour_map.h>
#include <pcl_ls3d/maps/drawing.h>
#include <pcl_ls3d/maps/raster.h>

#include <limits>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace maps {

/// \brief Text and layout of a raster map.
struct MapStyle
{
  std::string title;                  ///< bold first line
  std::vector<std::string> subtitle;  ///< lines under the title (statistics, dates)
  std::string unit = "m";             ///< unit of the values, over the colour bar
  std::string tick_format = "%+.2f";  ///< printf format of colour-bar labels
  /// Label the end ticks "≤ min" / "≥ max": values beyond the ramp take its end colours.
  bool clamp_labels = true;
  std::vector<std::string> legend;        ///< lines under the colour bar
  std::string footer;                     ///< last line (extent, cell, CRS)
  std::string length_unit = "m";          ///< unit of the coordinates (scale bar); empty: no scale bar
  Rgb no_data{200, 200, 200};             ///< colour of cells without a value
  int max_width = 760, max_height = 640;  ///< the map area fits in this (cells scaled)
};

/// Draws the raster (north up; cells enlarged by a whole factor, or averaged down when the
/// raster is larger than the map area). Where \a outline (a raster on the same grid) holds
/// values > 0.5, the border of those cells is drawn as a dark line on their outermost pixels
/// (e.g. deformed regions).
Drawing
renderRasterMap(const Raster& raster, const ColourMap& colours, const MapStyle& style,
                const Raster* outline = nullptr);

/// Colour of the outline renderRasterMap() draws around marked cells.
constexpr Rgb kOutlineColour{20, 20, 20};

/// \brief One distribution of a histogram chart.
struct HistogramSeries
{
  std::string label;
  std::vector<double> values;
  Rgb colour{33, 102, 172};
};

/// \brief Axes and text of a histogram chart.
struct HistogramStyle
{
  std::string title;
  std::string x_label = "discrepancy [m]";
  /// x range; NaN: the 0.5–99.5 % range of all values. Values outside are counted in the legend.
  double min = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
  int bins = 60;
  std::vector<double> marks;  ///< x positions of dashed reference lines (e.g. ±0.10, ±0.20)
  int width = 760, height = 420;
};

/// Overlaid histograms, each normalised to percent of its own values per bin (so series of
/// different sizes compare).
Drawing
renderHistogram(const std::vector<HistogramSeries>& series, const HistogramStyle& style);

/// \brief What drawScaleBar() drew: a round length in ground units and its length in pixels
///        (0: none, it would have been shorter than 8 pixels).
struct ScaleBar
{
  double length = 0.0;
  int pixels = 0;
};

/// Draws at (x, y) a scale bar of a round length (1, 2 or 5 × 10^k) near a quarter of
/// `map_width` pixels: four black and white parts 6 px high, "0" and "length unit" under its
/// ends; 30 px high in all. Used by renderRasterMap() and by pictures with their own layout.
ScaleBar
drawScaleBar(Drawing& drawing, int x, int y, int map_width, double ground_per_pixel, const std::string& unit);

/// Draws a bold "N" over an arrow pointing up, centred on x, 36 px high from y down.
void
drawNorthArrow(Drawing& drawing, int x, int y);

/// A "nice" tick step (1, 2 or 5 × 10^k) giving about `count` ticks over `range`.
double
niceStep(double range, int count);

}  // namespace maps
}  // namespace pcl_ls3d
