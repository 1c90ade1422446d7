#pragma once
/// \file terrain_cells.h
/// \brief Internal: the terrain around an object as a plane, from the lowest ground-filter point
///        per plan cell (object_classes.h takes heights above it), and the plane-spread test
///        shared with heightAboveTerrain (ground_filter.h). Not installed API.

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {
namespace detail {

/// \brief The hash key (planCellKey, voxel_index.h) of the plan cell of edge \a cell holding \a p.
std::uint64_t
planCellOf(const Eigen::Vector3f& p, double cell);

/// \brief Do the offsets behind the plane normal equations \a normal (upper triangle of
///        Σ r rᵀ, r = (1, dx, dy)) spread at least √min_variance across in every direction
///        (smallest eigenvalue of their covariance), from at least six points? Points along a
///        line or a narrow strip leave the slope across it to chance.
bool
spreadsAcross(const Eigen::Matrix3d& normal, double min_variance);

/// \brief The terrain around an object as a plane: z = level + tilt · (xy − centre). Where no
///        ground lies near, level is NaN and tilt 0.
struct TerrainPlane
{
  double level = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector2d tilt = Eigen::Vector2d::Zero();
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();

  /// z with the terrain's slope taken out: its height above the terrain is detrended − level.
  double
  detrended(const Eigen::Vector3f& p) const
  {
    return p.z() - tilt.dot(p.head<2>().cast<double>() - centre);
  }
};

/// \brief The lowest ground-filter point per plan cell and the object it belongs to (−1: none):
///        the terrain under and around an object, and what the other ground objects show around
///        a ground object.
class TerrainCells
{
public:
  TerrainCells(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
               const std::vector<char>& ground, double cell);

  /// \brief The terrain plane around the plan box [box_lo, box_hi] (cells within \a margin of
  ///        it): its slope from all of them (robust least squares, terrain_cells.cpp), its level
  ///        the median along that slope over the cells whose lowest point is not of object
  ///        \a except (−2: take all).
  TerrainPlane
  planeAround(const Eigen::Vector2d& box_lo, const Eigen::Vector2d& box_hi, double margin, int except) const;

private:
  struct Lowest
  {
    Eigen::Vector3f point;
    int object;
  };

  std::vector<Lowest>
  cellsNear(const Eigen::Vector2d& box_lo, const Eigen::Vector2d& box_hi, double margin) const;

  double cell_;
  std::unordered_map<std::uint64_t, Lowest> cells_;
};

}  // namespace detail
}  // namespace segmentation
}  // namespace pcl_ls3d
