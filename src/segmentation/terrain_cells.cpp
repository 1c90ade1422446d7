/// \file terrain_cells.cpp
/// \brief The terrain plane around an object from the lowest ground point per plan cell.

#include "terrain_cells.h"

#include <pcl_ls3d/common/voxel_index.h>
#include <pcl_ls3d/stats/descriptive.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {
namespace segmentation {
namespace detail {
namespace {

/// Cells more than this many robust sigmas off the plane (roofs the filter kept, holes) leave
/// the next fit; at least kMinTrimDistance, so that a smooth terrain keeps its small bumps.
constexpr double kTrimSigmas = 3.0;
constexpr double kMinTrimDistance = 0.5;
constexpr int kSlopeFits = 3;

/// Row (1, dx, dy) of the plane's design matrix for a point about \a centre.
Eigen::Vector3d
designRow(const Eigen::Vector3f& p, const Eigen::Vector2d& centre)
{
  const Eigen::Vector2d d = p.head<2>().cast<double>() - centre;
  return Eigen::Vector3d(1.0, d.x(), d.y());
}

/// Slope of the least-squares plane through \a lowest, refitted without the cells far off it.
/// Zero where the cells spread less than one cell (standard deviation) across in some
/// direction (a strip along a road tells nothing of the slope across it); if a refit no
/// longer spreads so, the last slope that did stands.
Eigen::Vector2d
robustSlope(const std::vector<Eigen::Vector3f>& lowest, const Eigen::Vector2d& centre, double cell)
{
  std::vector<char> kept(lowest.size(), 1);
  Eigen::Vector2d slope = Eigen::Vector2d::Zero();
  for (int fit = 0; fit < kSlopeFits; ++fit) {
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < lowest.size(); ++i)
      if (kept[i]) {
        const Eigen::Vector3d row = designRow(lowest[i], centre);
        normal += row * row.transpose();
        rhs += row * lowest[i].z();
      }
    if (!spreadsAcross(normal, cell * cell))
      return slope;
    const Eigen::Vector3d plane = normal.ldlt().solve(rhs);  // a + b·dx + c·dy
    slope = plane.tail<2>();
    if (fit + 1 == kSlopeFits)
      break;
    std::vector<double> residuals(lowest.size());
    for (std::size_t i = 0; i < lowest.size(); ++i)
      residuals[i] = lowest[i].z() - plane.dot(designRow(lowest[i], centre));
    const double limit = std::max(kMinTrimDistance, kTrimSigmas * stats::mad(residuals, true));
    for (std::size_t i = 0; i < lowest.size(); ++i)
      kept[i] = std::abs(residuals[i]) <= limit;
  }
  return slope;
}

}  // namespace

std::uint64_t
planCellOf(const Eigen::Vector3f& p, double cell)
{
  return planCellKey(planCellCoordinate(p.x(), cell), planCellCoordinate(p.y(), cell));
}

bool
spreadsAcross(const Eigen::Matrix3d& normal, double min_variance)
{
  const double n = normal(0, 0);
  if (n < 6.0)
    return false;
  const Eigen::Vector2d mean(normal(0, 1) / n, normal(0, 2) / n);
  Eigen::Matrix2d spread;
  spread << normal(1, 1) / n - mean.x() * mean.x(), normal(1, 2) / n - mean.x() * mean.y(), 0.0,
      normal(2, 2) / n - mean.y() * mean.y();
  spread(1, 0) = spread(0, 1);
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(spread, Eigen::EigenvaluesOnly).eigenvalues()(0) >=
         min_variance;
}

TerrainCells::TerrainCells(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
                           const std::vector<char>& ground, double cell)
    : cell_(cell)
{
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (!ground[p] || !points[p].allFinite())
      continue;
    const Lowest here{points[p], labels[p]};
    const auto [it, fresh] = cells_.try_emplace(planCellOf(points[p], cell_), here);
    if (!fresh && here.point.z() < it->second.point.z())
      it->second = here;
  }
}

TerrainPlane
TerrainCells::planeAround(const Eigen::Vector2d& box_lo, const Eigen::Vector2d& box_hi, double margin,
                          int except) const
{
  const std::vector<Lowest> near = cellsNear(box_lo, box_hi, margin);
  std::vector<Eigen::Vector3f> lowest(near.size());
  for (std::size_t i = 0; i < near.size(); ++i)
    lowest[i] = near[i].point;
  TerrainPlane plane;
  plane.centre = 0.5 * (box_lo + box_hi);
  plane.tilt = robustSlope(lowest, plane.centre, cell_);
  std::vector<double> levels;
  for (const Lowest& l : near)
    if (l.object != except)
      levels.push_back(plane.detrended(l.point));
  plane.level = stats::median(std::move(levels));
  return plane;
}

std::vector<TerrainCells::Lowest>
TerrainCells::cellsNear(const Eigen::Vector2d& box_lo, const Eigen::Vector2d& box_hi, double margin) const
{
  const std::int64_t x0 = planCellCoordinate(box_lo.x() - margin, cell_);
  const std::int64_t x1 = planCellCoordinate(box_hi.x() + margin, cell_);
  const std::int64_t y0 = planCellCoordinate(box_lo.y() - margin, cell_);
  const std::int64_t y1 = planCellCoordinate(box_hi.y() + margin, cell_);
  std::vector<Lowest> near;
  // Scan the smaller of the box's cells and the occupied cells.
  if (static_cast<double>(x1 - x0 + 1) * static_cast<double>(y1 - y0 + 1) >
      static_cast<double>(cells_.size())) {
    for (const auto& [key, lowest] : cells_) {
      const std::int64_t x = static_cast<std::int32_t>(key >> 32);
      const std::int64_t y = static_cast<std::int32_t>(key & 0xffffffffu);
      if (x >= x0 && x <= x1 && y >= y0 && y <= y1)
        near.push_back(lowest);
    }
  } else {
    for (std::int64_t x = x0; x <= x1; ++x)
      for (std::int64_t y = y0; y <= y1; ++y)
        if (const auto it = cells_.find(planCellKey(x, y)); it != cells_.end())
          near.push_back(it->second);
  }
  return near;
}

}  // namespace detail
}  // namespace segmentation
}  // namespace pcl_ls3d
