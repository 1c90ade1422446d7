#pragma once
/// \file surface_matching_core.h
/// \brief The PCL-free LS3D pair adjustment (Zuo et al. 2012, §2), composed of the engine's
///        stages (docs/ARCHITECTURE.md): parameter blocks and frames (parameter_block.h) →
///        conjugate points (pair_matcher.h) → robust weights (observation_weighting.h, eq. 15) →
///        normal equations (eq. 8) → Gauss–Markoff solve with a-priori observations
///        (gauss_markov.h, eqs. 9–11) → iteration control (iteration_control.h); then precision
///        (eq. 14, spatial_precision.h) and reliability (redundancy numbers).

#include <pcl_ls3d/adjustment/adjustment_report.h>
#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/adjustment/observation_weighting.h>
#include <pcl_ls3d/adjustment/pair_matcher.h>
#include <pcl_ls3d/estimators/robust_estimator.h>
#include <pcl_ls3d/rules/conjugate_rule.h>

#include <functional>
#include <utility>
#include <vector>

namespace pcl_ls3d {

/// \brief Regular thinning: indices of one point per cubic voxel of edge `step` (the first one
///        met). step ≤ 0 returns every index, and so does a step too fine for the points'
///        extent (over 2^52 voxels along an axis: finer than the coordinates resolve).
std::vector<int>
thinByVoxel(const std::vector<Eigen::Vector3d>& points, double step);

/// \brief Optional per-iteration hooks of a wrapper (the PCL class uses them for PCL's
///        correspondence rejectors, euclidean fitness epsilon and visualisation callback).
///        `pose` is the current source → target 4×4 (cloud coordinates).
struct IterationHooks
{
  /// After stage 2: set keep[j] = 0 to drop observation j before weighting (keep starts all 1).
  std::function<void(const Eigen::Matrix4d& pose, const ObservationSet& observations,
                     std::vector<char>& keep)>
      filter;
  /// After each update, with the pose after it and the observations it used; returning true
  /// ends the adjustment as CONVERGED.
  std::function<bool(const IterationRecord& record, const Eigen::Matrix4d& pose,
                     const ObservationSet& observations)>
      after_iteration;
};

/// \brief Runs LS3D pair adjustments. Not thread-safe itself; parallel inside (OpenMP). Buffers
///        persist across runs.
class SurfaceMatchingCore
{
public:
  /// \param[in] source source points in source-cloud coordinates (finite, already thinned)
  /// \param[in] source_indices index of each point in the caller's cloud (for the report)
  /// \param[in] target the target surface (cloud coordinates)
  /// \param[in] guess initial 4×4 similarity mapping source into target coordinates
  AdjustmentReport
  run(const std::vector<Eigen::Vector3d>& source, const std::vector<int>& source_indices,
      const TargetSurface& target, const ConjugateRule& rule, const RobustEstimator& estimator,
      const AdjustmentSettings& settings, const Eigen::Matrix4d& guess);

  /// Hooks for the following runs (empty functions: none).
  void
  setHooks(IterationHooks hooks)
  {
    hooks_ = std::move(hooks);
  }

private:
  IterationHooks hooks_;
  std::vector<Eigen::Vector3d> reduced_;  ///< source points minus the source block's origin
  PairMatcher matcher_;
  ObservationWeighting weighting_;
};

}  // namespace pcl_ls3d
