#pragma once
/// \file voxel_index.h
/// \brief A hashed voxel grid over a point set for fixed-radius and k-nearest searches, and the
///        point spacing and dominant plane of a cloud (deformation regions, areas, M3C2-style
///        neighbourhoods, neighbour-difference noise scales). PCL-free; searches are const and thread-safe.

#include <Eigen/Core>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace pcl_ls3d {

/// \brief Mean point spacing s = √(A / n) over the largest of the three axis-plane projections
///        of the points' box (terrain: xy; a wall: xz or yz), and that plane's normal axis
///        (2 = z for terrain). Non-finite points are ignored; s = 0 for fewer than 2 points.
struct CloudSpacing
{
  double spacing = 0.0;
  int normal_axis = 2;
};

/// \param[in] axis the plane's normal axis (0 x, 1 y, 2 z), or −1: the box's largest projection.
///  The box estimate is refined twice by the area of the occupied cells of edge s (a rotated or
///  irregular footprint occupies less than its box).
CloudSpacing
cloudSpacing(const std::vector<Eigen::Vector3d>& points, int axis = -1);

/// \brief Number of distinct square cells of edge `cell` that the finite points occupy in the
///        plane of axes `a` and `b` (0 x, 1 y, 2 z): the footprint's area is that times cell².
std::size_t
occupiedCells(const std::vector<Eigen::Vector3d>& points, int a, int b, double cell);

/// Beyond 2^52 cells a double no longer resolves a whole cell, so coordinates stop there.
constexpr std::int64_t kVoxelCoordinateLimit = std::int64_t{1} << 52;

/// \brief floor(x / cell), saturated at ±kVoxelCoordinateLimit (and 0 for NaN). A plain cast
///        overflows (undefined behaviour) once x / cell passes 9.2e18, e.g. a 1e-25 m cell on
///        metre coordinates; saturation keeps the order, so range searches stay correct.
std::int64_t
voxelCoordinate(double x, double cell);

/// \brief voxelCoordinate() saturated to the 32-bit range that planCellKey() packs: a plan
///        cell's column or row for hashed 2-D grids (only absurd outliers are clamped; they
///        share edge cells far from any data).
std::int64_t
planCellCoordinate(double x, double cell);

/// \brief One hash key for the plan cell (u, v) (planCellCoordinate()s; values outside 32 bits
///        are saturated first, so keys and cell ranges agree).
std::uint64_t
planCellKey(std::int64_t u, std::int64_t v);

/// \brief Points hashed into cubic voxels of edge `cell` (non-finite points are left out).
class VoxelIndex
{
public:
  VoxelIndex(const std::vector<Eigen::Vector3d>& points, double cell);

  /// Indices of the points within `radius` of `query` (any order).
  void
  radiusSearch(const Eigen::Vector3d& query, double radius, std::vector<int>& out) const;

  /// The k nearest points of `query` (closest first; fewer when the cloud has fewer).
  void
  nearestK(const Eigen::Vector3d& query, int k, std::vector<int>& out) const;

  double
  cell() const
  {
    return cell_;
  }

private:
  std::int64_t
  key(const Eigen::Vector3d& p) const;
  static std::int64_t
  key(std::int64_t x, std::int64_t y, std::int64_t z);

  const std::vector<Eigen::Vector3d>& points_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> voxels_;
  std::size_t stored_ = 0;
};

}  // namespace pcl_ls3d
