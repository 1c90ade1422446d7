#pragma once
/// \file footprints.h
/// \brief Stage "plan" of the strip adjustment: each strip's 2-D footprint on one raster over
///        the block (sparse: the occupied cells and their point counts), and from them the
///        overlap graph: for every pair of strips the common cells, their area and the points
///        of each strip in them. Pairs with too little common area are kept in the list,
///        marked skipped with the reason.

#include <pcl_ls3d/maps/raster.h>
#include <pcl_ls3d/strips/strip.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pcl_ls3d {
namespace strips {

/// \brief Occupied cells of every strip on one grid (block coordinates).
class Footprints
{
public:
  /// One (cell id, points) pair per occupied cell, sorted by cell id.
  using Cells = std::vector<std::pair<std::uint64_t, std::uint32_t>>;

  /// Builds the footprints; cell ≤ 0 chooses 3 / √(density of the sparsest strip).
  static Footprints
  build(const std::vector<Strip>& strips, double cell = 0.0);
  /// Builds the footprints on a given grid (a distributed job re-creating the plan's cells).
  static Footprints
  build(const std::vector<Strip>& strips, const maps::GridGeometry& grid);

  const maps::GridGeometry&
  grid() const
  {
    return grid_;
  }
  double
  cell() const
  {
    return grid_.cell;
  }
  std::size_t
  strips() const
  {
    return cells_.size();
  }
  const Cells&
  cells(std::size_t strip) const
  {
    return cells_[strip];
  }
  /// Points per unit area of a strip over its occupied cells.
  double
  density(std::size_t strip) const;
  /// Cell id of a block position (−1 outside the grid).
  std::int64_t
  cellId(double x, double y) const;

private:
  maps::GridGeometry grid_;
  std::vector<Cells> cells_;
};

/// \brief One pair of strips with common cells.
struct Overlap
{
  int i = -1, j = -1;  ///< strip indices, i < j
  std::size_t common_cells = 0;
  double area = 0.0;                       ///< common_cells × cell² [unit²]
  std::size_t points_i = 0, points_j = 0;  ///< points of each strip in the common cells
  bool used = true;
  std::string skip_reason;           ///< why it is not used
  std::vector<std::uint64_t> cells;  ///< the common cell ids (sorted)
};

/// Pairs of strips with at least one common cell, ordered by (i, j); those below
/// `min_area` are marked skipped.
std::vector<Overlap>
findOverlaps(const Footprints& footprints, double min_area);

/// Connected parts of the graph of used overlaps: part index per strip (−1 for a strip with no
/// used overlap), parts numbered from 0 in order of their smallest strip.
std::vector<int>
connectedParts(std::size_t strips, const std::vector<Overlap>& overlaps);

}  // namespace strips
}  // namespace pcl_ls3d
