#pragma once
/// \file colour_map.h
/// \brief Value → colour for maps: piecewise-linear colour ramps whose stops may jump (two stops
///        at one value), so one class serves a smooth diverging ramp, a sequential ramp and a
///        banded ramp that makes tolerance classes visible, as lasoverlap does (LAStools).

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace maps {

/// \brief An 8-bit sRGB colour.
struct Rgb
{
  std::uint8_t r = 0, g = 0, b = 0;

  bool
  operator==(const Rgb& o) const
  {
    return r == o.r && g == o.g && b == o.b;
  }
  bool
  operator!=(const Rgb& o) const
  {
    return !(*this == o);
  }
  /// From 0xRRGGBB.
  static Rgb
  hex(std::uint32_t v)
  {
    return {static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 8),
            static_cast<std::uint8_t>(v)};
  }
};

/// \brief A colour ramp over [min(), max()]; values outside are clamped to the end colours.
class ColourMap
{
public:
  struct Stop
  {
    double value = 0.0;
    Rgb colour;
  };

  /// `stops` in non-decreasing order of value (at least two, first < last). Two stops at the
  /// same value make a step: values at or above it take the second colour. Invalid stops give
  /// an empty map (valid() false).
  explicit ColourMap(std::vector<Stop> stops, std::string name = "");

  bool
  valid() const
  {
    return stops_.size() >= 2;
  }
  Rgb
  colour(double value) const;
  double
  min() const
  {
    return stops_.front().value;
  }
  double
  max() const
  {
    return stops_.back().value;
  }
  const std::string&
  name() const
  {
    return name_;
  }
  /// The stops, in non-decreasing order of value (empty when invalid).
  const std::vector<Stop>&
  stops() const
  {
    return stops_;
  }
  /// Values labelled on a colour bar (default: five evenly spaced, ends included).
  const std::vector<double>&
  ticks() const
  {
    return ticks_;
  }
  void
  setTicks(std::vector<double> ticks)
  {
    ticks_ = std::move(ticks);
  }
  /// Values where the colour jumps (class boundaries), drawn as lines on a colour bar.
  std::vector<double>
  steps() const;

  /// Smooth blue–white–red over [−limit, limit] (ColorBrewer RdBu): negative blue, positive red.
  static ColourMap
  diverging(double limit);
  /// lasoverlap-style classes of a signed difference: |d| < inner nearly white (light blue to
  /// light red, so patterns inside the tolerance stay visible), inner ≤ |d| < outer medium
  /// blue / orange, |d| ≥ outer saturated blue / red; the ramp ends at ±1.5 outer.
  static ColourMap
  bandedDiverging(double inner = 0.10, double outer = 0.20);
  /// Viridis over [lo, hi] (perceptually uniform, colour-blind safe).
  static ColourMap
  sequential(double lo, double hi);

private:
  std::vector<Stop> stops_;
  std::vector<double> ticks_;
  std::string name_;
};

}  // namespace maps
}  // namespace pcl_ls3d
