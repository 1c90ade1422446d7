#include <pcl_ls3d/maps/colour_map.h>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {
namespace maps {

namespace {

// ColorBrewer RdBu, 11 classes, from dark red to dark blue (Brewer, Penn State, Apache-2.0).
constexpr std::uint32_t kRdBu[11] = {0x67001f, 0xb2182b, 0xd6604d, 0xf4a582, 0xfddbc7, 0xf7f7f7,
                                     0xd1e5f0, 0x92c5de, 0x4393c3, 0x2166ac, 0x053061};
// Viridis (matplotlib, CC0), 9 samples from dark purple to yellow.
constexpr std::uint32_t kViridis[9] = {0x440154, 0x472c7a, 0x3b518b, 0x2c718e, 0x21908d,
                                       0x27ad81, 0x5cc863, 0xaadc32, 0xfde725};

std::uint8_t
mix(std::uint8_t a, std::uint8_t b, double t)
{
  return static_cast<std::uint8_t>(std::lround(a + (static_cast<double>(b) - a) * t));
}

bool
validStops(const std::vector<ColourMap::Stop>& stops)
{
  if (stops.size() < 2 || !(stops.front().value < stops.back().value))
    return false;
  for (std::size_t i = 0; i < stops.size(); ++i) {
    if (!std::isfinite(stops[i].value))
      return false;
    if (i > 0 && stops[i].value < stops[i - 1].value)
      return false;
  }
  return true;
}

std::vector<double>
evenTicks(double lo, double hi)
{
  std::vector<double> t;
  for (int i = 0; i <= 4; ++i)
    t.push_back(lo + (hi - lo) * i / 4.0);
  return t;
}

}  // namespace

ColourMap::ColourMap(std::vector<Stop> stops, std::string name) : name_(std::move(name))
{
  if (!validStops(stops))
    return;
  stops_ = std::move(stops);
  ticks_ = evenTicks(min(), max());
}

Rgb
ColourMap::colour(double v) const
{
  if (stops_.empty())
    return {};
  if (!(v > stops_.front().value))  // also NaN
    return stops_.front().colour;
  if (v >= stops_.back().value)
    return stops_.back().colour;
  // First stop strictly above v; at a step (equal values) v takes the upper colour.
  const auto hi =
      std::upper_bound(stops_.begin(), stops_.end(), v, [](double x, const Stop& s) { return x < s.value; });
  const Stop& b = *hi;
  const Stop& a = *(hi - 1);
  const double t = b.value > a.value ? (v - a.value) / (b.value - a.value) : 1.0;
  return {mix(a.colour.r, b.colour.r, t), mix(a.colour.g, b.colour.g, t), mix(a.colour.b, b.colour.b, t)};
}

std::vector<double>
ColourMap::steps() const
{
  std::vector<double> out;
  for (std::size_t i = 1; i < stops_.size(); ++i)
    if (stops_[i].value == stops_[i - 1].value && stops_[i].colour != stops_[i - 1].colour)
      out.push_back(stops_[i].value);
  return out;
}

ColourMap
ColourMap::diverging(double limit)
{
  std::vector<Stop> s;
  for (int i = 0; i < 11; ++i)
    s.push_back({-limit + 2.0 * limit * i / 10.0, Rgb::hex(kRdBu[10 - i])});
  return ColourMap(std::move(s), "diverging RdBu");
}

ColourMap
ColourMap::bandedDiverging(double inner, double outer)
{
  const double o = outer, i = inner, e = 1.5 * outer;
  auto c = [](int k) { return Rgb::hex(kRdBu[k]); };
  ColourMap m({{-e, c(10)},
               {-o, c(9)},  // saturated blue: d ≤ −outer
               {-o, c(8)},
               {-i, c(7)},  // medium blue: −outer < d ≤ −inner
               {-i, c(6)},
               {0, c(5)},
               {i, c(4)},  // within tolerance: nearly white
               {i, c(3)},
               {o, c(2)},  // orange: inner ≤ d < outer
               {o, c(1)},
               {e, c(0)}},  // saturated red: d ≥ outer
              "banded RdBu");
  m.setTicks({-e, -o, -i, 0.0, i, o, e});
  return m;
}

ColourMap
ColourMap::sequential(double lo, double hi)
{
  std::vector<Stop> s;
  for (int i = 0; i < 9; ++i)
    s.push_back({lo + (hi - lo) * i / 8.0, Rgb::hex(kViridis[i])});
  return ColourMap(std::move(s), "viridis");
}

}  // namespace maps
}  // namespace pcl_ls3d
