#pragma once
/// \file ground_filter.h
/// \brief The progressive morphological ground filter (Zhang et al. 2003, the algorithm of
///        pcl::ApproximateProgressiveMorphologicalFilter, with an opened surface that follows the
///        slope within each cell) on a horizontal grid of lowest points,
///        with separable O(1)-per-cell min/max filters so that windows wider than a building
///        stay cheap at a million points. PCL-free; used by the object level of IMRG
///        (object_assembly.h).

#include <Eigen/Core>

#include <vector>

namespace pcl_ls3d {
namespace segmentation {

/// \brief Lowest z per cell of a horizontal grid over the finite points (NaN for empty cells;
///        no cell at all when no point is finite).
class LowestPointGrid
{
public:
  LowestPointGrid(const std::vector<Eigen::Vector3f>& points, double cell);

  int
  rows() const
  {
    return rows_;
  }
  int
  cols() const
  {
    return cols_;
  }
  double
  cell() const
  {
    return cell_;
  }
  /// Row-major cell index of a point (clamped into the grid).
  int
  cellOf(const Eigen::Vector3f& p) const;
  /// Lowest z per cell, row-major; NaN where no point fell.
  const std::vector<float>&
  lowest() const
  {
    return lowest_;
  }
  /// Index of the point holding each cell's lowest z; −1 where no point fell.
  const std::vector<int>&
  lowestPoint() const
  {
    return lowest_point_;
  }

private:
  double cell_ = 1.0;
  Eigen::Vector2d min_ = Eigen::Vector2d::Zero();
  int rows_ = 0, cols_ = 0;
  std::vector<float> lowest_;
  std::vector<int> lowest_point_;
};

/// \brief Settings of groundPoints(); lengths in cloud units.
struct GroundFilterSettings
{
  double cell = 1.0;              ///< grid cell
  double max_window = 60.0;       ///< largest structuring element: wider than any building
  double slope = 0.5;             ///< terrain slope allowed between two window sizes
  double initial_distance = 0.3;  ///< height above the opened surface still ground (noise)
  double max_distance = 3.0;      ///< cap of the height threshold (lowest roof height)
};

/// \brief Progressive morphological filter: windows of 3, 5, 9, 17, ... cells (up to
///        max_window); at each, the grid of lowest points is opened (min then max filter,
///        separable, O(1) per cell with a monotone queue) and a point higher than the opened
///        surface by more than dh_k = min(max_distance, initial + slope · (w_k − w_{k−1}) · cell)
///        (dh_0 = initial) is not ground. Empty cells take the values their windows give them.
///        The opened surface is not flat within a cell: it passes through the xy of the cell's
///        lowest point at the cell's opened height, with the slope the opened grid has there
///        (per axis the one-sided difference smaller in magnitude, 0 where the two disagree in
///        sign: a step or a ridge adds no tilt), so that points on a slope steeper than
///        initial / cell are not cut off at the top of each cell.
/// \return per point: 1 ground, 0 not ground (also for non-finite points)
std::vector<char>
groundPoints(const std::vector<Eigen::Vector3f>& points, const GroundFilterSettings& settings);

/// \brief Height of points above the terrain right under them: the least-squares plane of the
///        ground points (\a ground 1) in a square window about 2 \a half_width wide around each
///        (the 3 × 3 cells of side 2/3 \a half_width around its own). Finer than the filter's
///        opened surface, which keeps everything up to its initial distance above the lowest
///        points. Non-finite points are skipped.
/// \param[in] wanted per point: 1 to compute its height
/// \return per point: height above that plane; NaN where not wanted, where fewer than six
///         ground points lie in the window, or where they lie along a line or a strip too thin
///         to give the slope across it (spread below 0.1 cell); all NaN when the sizes of
///         \a ground or \a wanted differ from \a points
std::vector<float>
heightAboveTerrain(const std::vector<Eigen::Vector3f>& points, const std::vector<char>& ground,
                   const std::vector<char>& wanted, double half_width);

}  // namespace segmentation
}  // namespace pcl_ls3d
