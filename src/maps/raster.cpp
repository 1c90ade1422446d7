#include <pcl_ls3d/maps/raster.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace maps {

GridGeometry
GridGeometry::covering(const Eigen::Vector2d& min, const Eigen::Vector2d& max, double cell)
{
  GridGeometry g;
  if (!(cell > 0.0) || !min.allFinite() || !max.allFinite() || (max - min).minCoeff() < 0.0)
    return g;
  g.cell = cell;
  g.min_x = std::floor(min.x() / cell) * cell;
  g.max_y = std::ceil(max.y() / cell) * cell;
  g.cols = static_cast<int>(std::floor((max.x() - g.min_x) / cell)) + 1;
  g.rows = static_cast<int>(std::floor((g.max_y - min.y()) / cell)) + 1;
  return g;
}

bool
GridGeometry::cellOf(double x, double y, int& col, int& row) const
{
  const double c = std::floor((x - min_x) / cell), r = std::floor((max_y - y) / cell);
  if (!(c >= 0.0 && r >= 0.0 && c < cols && r < rows))
    return false;
  col = static_cast<int>(c);
  row = static_cast<int>(r);
  return true;
}

std::array<double, 6>
GridGeometry::geoTransform() const
{
  return {min_x, cell, 0.0, max_y, 0.0, -cell};
}

Raster::Raster(const GridGeometry& g) : grid(g), values(g.size(), std::numeric_limits<float>::quiet_NaN())
{}

std::size_t
Raster::validCells() const
{
  return static_cast<std::size_t>(
      std::count_if(values.begin(), values.end(), [](float v) { return std::isfinite(v); }));
}

std::pair<float, float>
Raster::range() const
{
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (float v : values)
    if (std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (lo > hi)
    return {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::quiet_NaN()};
  return {lo, hi};
}

RasterAccumulator::RasterAccumulator(const GridGeometry& grid, Mode mode)
    : grid_(grid), mode_(mode), value_(grid.size(), 0.0), count_(grid.size(), 0)
{}

void
RasterAccumulator::add(double x, double y, double value)
{
  int col = 0, row = 0;
  if (!std::isfinite(value) || !grid_.cellOf(x, y, col, row))
    return;
  const std::size_t k =
      static_cast<std::size_t>(row) * static_cast<std::size_t>(grid_.cols) + static_cast<std::size_t>(col);
  if (mode_ == Mode::MEAN)
    value_[k] += value;
  else if (count_[k] == 0 || std::abs(value) > std::abs(value_[k]))
    value_[k] = value;
  ++count_[k];
}

void
RasterAccumulator::addRaster(const Raster& raster)
{
  for (int r = 0; r < raster.grid.rows; ++r)
    for (int c = 0; c < raster.grid.cols; ++c) {
      const Eigen::Vector2d x = raster.grid.centre(c, r);
      add(x.x(), x.y(), raster.at(c, r));
    }
}

Raster
RasterAccumulator::result(std::size_t min_count) const
{
  Raster out(grid_);
  for (std::size_t k = 0; k < out.values.size(); ++k)
    if (count_[k] >= std::max<std::size_t>(1, min_count))
      out.values[k] = static_cast<float>(mode_ == Mode::MEAN ? value_[k] / count_[k] : value_[k]);
  return out;
}

}  // namespace maps
}  // namespace pcl_ls3d
