#pragma once
/// \file surface_matching_core.h
/// \brief The PCL-free LS3D engine (Zuo et al. 2012, §2): iterate conjugate points (rule) →
///        robust weights (eq. 15) → normal equations (eq. 8) → Gauss–Markoff solve with a-priori
///        observations (eqs. 9–11) → update, until the angle changes fall below ε; then
///        precision (eq. 14) and redundancy numbers. Buffers persist across runs.

#include <pcl_ls3d/adjustment/adjustment_report.h>
#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/adjustment/overlap_grid.h>
#include <pcl_ls3d/adjustment/similarity_jacobian.h>
#include <pcl_ls3d/estimators/robust_estimator.h>
#include <pcl_ls3d/rules/conjugate_rule.h>

#include <vector>

namespace pcl_ls3d {

/// \brief Regular thinning: indices of one point per cubic voxel of edge `step` (the first one
///        met). step ≤ 0 returns every index.
std::vector<int>
thinByVoxel(const std::vector<Eigen::Vector3d>& points, double step);

/// \brief Runs LS3D adjustments. Not thread-safe itself; parallel inside (OpenMP).
class SurfaceMatchingCore
{
public:
  /// \param[in] source source points in source-cloud coordinates (finite, already thinned)
  /// \param[in] source_indices index of each point in the caller's cloud (for the report)
  /// \param[in] target the target surface (cloud coordinates)
  /// \param[in] guess initial 4×4 similarity mapping source into target coordinates
  AdjustmentReport
  run(const std::vector<Eigen::Vector3d>& source,
      const std::vector<int>& source_indices,
      const TargetSurface& target,
      const ConjugateRule& rule,
      const RobustEstimator& estimator,
      const AdjustmentSettings& settings,
      const Eigen::Matrix4d& guess);

private:
  /// Step 1 of an iteration: the conjugate observations of every `every`-th transformed source
  /// point (skipping those that missed last time when skip_missed), compacted into obs_*;
  /// returns their number.
  std::size_t
  findCorrespondences(const SimilarityLinearization& lin, const Eigen::Vector3d& o_t,
                      const TargetSurface& target, const ConjugateRule& rule, double max_distance,
                      std::size_t every, bool skip_missed, int stride);

  // Reused buffers (grow only): reduced source, per-point rule caches, observation slots.
  std::vector<Eigen::Vector3d> reduced_;
  std::vector<CorrespondenceCache> caches_;
  std::vector<unsigned char> counts_;
  std::vector<unsigned char> missed_;  ///< no correspondence at the point's last search
  std::vector<Eigen::Vector3d> obs_u_;
  std::vector<double> obs_l_;
  std::vector<int> obs_point_;
  Eigen::VectorXd weights_, sigma_v_;
  OverlapGrid grid_;
};

}  // namespace pcl_ls3d
