#pragma once
/// \file overlap_grid.h
/// \brief Overlap culling for the LS3D engine: a 2-D grid over the target's XY extent holding,
///        per cell, the z range of the target points within `reach` of it. A query point whose
///        cell range does not contain its z has no target point within `reach` (the maximum
///        correspondence distance), so no rule may give it a correspondence and the engine skips
///        its neighbour search. In strip adjustment ~80 % of a strip lies outside the shared
///        band; this turns their k-NN searches into one table look-up each.

#include <pcl_ls3d/rules/target_surface.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_ls3d {

/// \brief Conservative "is any target point within reach?" test (false positives only).
class OverlapGrid
{
public:
  /// Builds the grid. reach must be finite and > 0; the cell edge is reach, enlarged when the
  /// grid would exceed max_cells (the test stays conservative: the dilation covers reach).
  /// Returns false (grid unusable, every query passes) for an empty target, an invalid reach or
  /// one larger than the target's XY diagonal.
  bool
  build(const TargetSurface& target, double reach, std::size_t max_cells = std::size_t(1) << 24);

  /// True when a target point may lie within reach of p (always true when not built).
  bool
  mayOverlap(const Eigen::Vector3d& p) const
  {
    if (!built_)
      return true;
    const double fx = (p.x() - x0_) * inv_cell_, fy = (p.y() - y0_) * inv_cell_;
    if (!(fx >= 0.0 && fy >= 0.0 && fx < nx_ && fy < ny_))
      return false;
    const std::size_t c =
        static_cast<std::size_t>(fy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(fx);
    return p.z() >= zlo_[c] && p.z() <= zhi_[c];
  }

  bool
  built() const
  {
    return built_;
  }

private:
  bool built_ = false;
  double x0_ = 0.0, y0_ = 0.0, inv_cell_ = 1.0;
  long nx_ = 0, ny_ = 0;
  std::vector<float> zlo_, zhi_;  ///< z range (grown by reach) of target points near the cell
};

}  // namespace pcl_ls3d
