#pragma once
/// \file raster.h
/// \brief A georeferenced grid of float values, north up, as a GeoTIFF holds it: cell (col, row)
///        covers x ∈ [min_x + col·cell, min_x + (col+1)·cell), y ∈ (max_y − (row+1)·cell,
///        max_y − row·cell]. NaN marks "no data". Coordinates are those of the data (e.g. the
///        file coordinates of a LAS, in double), so a map lands where its points are.

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace pcl_ls3d {
namespace maps {

/// \brief The geometry of a north-up grid (GDAL's geotransform with no rotation).
struct GridGeometry
{
  double min_x = 0.0;  ///< west edge of column 0
  double max_y = 0.0;  ///< north edge of row 0
  double cell = 1.0;   ///< cell edge (same unit as x, y)
  int cols = 0, rows = 0;

  /// The smallest grid of `cell` whose cells cover [min, max] (corners snapped to multiples of
  /// the cell, so grids of different extents but equal cells line up).
  static GridGeometry
  covering(const Eigen::Vector2d& min, const Eigen::Vector2d& max, double cell);

  bool
  valid() const
  {
    return cell > 0.0 && cols > 0 && rows > 0;
  }
  std::size_t
  size() const
  {
    return static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows);
  }
  /// Column and row of a position; false when outside the grid.
  bool
  cellOf(double x, double y, int& col, int& row) const;
  /// Centre of a cell.
  Eigen::Vector2d
  centre(int col, int row) const
  {
    return {min_x + (col + 0.5) * cell, max_y - (row + 0.5) * cell};
  }
  double
  maxX() const
  {
    return min_x + cols * cell;
  }
  double
  minY() const
  {
    return max_y - rows * cell;
  }
  /// GDAL geotransform {min_x, cell, 0, max_y, 0, −cell}.
  std::array<double, 6>
  geoTransform() const;
};

/// \brief Values on a grid; NaN = no data.
struct Raster
{
  GridGeometry grid;
  std::vector<float> values;  ///< row-major, row 0 north

  Raster() = default;
  explicit Raster(const GridGeometry& g);

  float&
  at(int col, int row)
  {
    return values[static_cast<std::size_t>(row) * static_cast<std::size_t>(grid.cols) +
                  static_cast<std::size_t>(col)];
  }
  float
  at(int col, int row) const
  {
    return values[static_cast<std::size_t>(row) * static_cast<std::size_t>(grid.cols) +
                  static_cast<std::size_t>(col)];
  }
  /// Number of cells holding a value.
  std::size_t
  validCells() const;
  /// Smallest and largest value (NaN, NaN when empty).
  std::pair<float, float>
  range() const;
};

/// \brief Builds a raster from scattered samples: per cell the mean, or the value of largest
///        magnitude (a conservative view where several overlaps share a cell).
class RasterAccumulator
{
public:
  enum class Mode
  {
    MEAN,
    MAX_ABS
  };

  explicit RasterAccumulator(const GridGeometry& grid, Mode mode = Mode::MEAN);

  /// Adds a sample at (x, y); samples outside the grid or non-finite are ignored.
  void
  add(double x, double y, double value);
  /// Adds every valid cell of a raster on the same grid geometry (cell by cell).
  void
  addRaster(const Raster& raster);
  /// Cells with fewer than `min_count` samples are no data.
  Raster
  result(std::size_t min_count = 1) const;
  const GridGeometry&
  grid() const
  {
    return grid_;
  }

private:
  GridGeometry grid_;
  Mode mode_;
  std::vector<double> value_;
  std::vector<std::uint32_t> count_;
};

}  // namespace maps
}  // namespace pcl_ls3d
