#pragma once
/// \file quality_gate.h
/// \brief The last stage of an adjustment: may the result be trusted? Convergence alone says
///        only that the steps became small; a wrong fit converges too. The gate compares σ0
///        with the noise both surfaces carry (their own local roughness), checks how much of the
///        overlap holds the fit and how much the estimator threw away, how far the estimate
///        moved, and whether a free scale stayed plausible. A result that fails is reported as
///        STALLED (it never left the initial guess), UNRELIABLE or IMPLAUSIBLE_SCALE, with the
///        figures in AdjustmentReport::quality and the reasons in the message; hasConverged()
///        of the PCL class is then false and the tools exit non-zero.

#include <pcl_ls3d/adjustment/adjustment_report.h>
#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/adjustment/observation_set.h>

#include <Eigen/Geometry>

#include <string>

namespace pcl_ls3d {

/// \brief What the gate measures a finished adjustment with.
struct QualityInputs
{
  double sigma0 = 0.0;                    ///< σ̂0 of the last solve
  double normal_sigma = 0.0;              ///< normalComponentSigma() of the last solve (0: n/a)
  double source_noise = 0.0;              ///< σ_s (surface_noise.h)
  double target_noise = 0.0;              ///< σ_t near the conjugate points
  double spacing = 0.0;                   ///< mean target point spacing: σ0 below 1e-3 of it is an exact fit
  std::size_t candidates = 0;             ///< source points over the target's extent
  std::size_t correspondences = 0;        ///< observations of the last iteration
  std::size_t used = 0;                   ///< of them with non-zero weight
  double start_scale = 0.0;               ///< 1.4826 · median |l| of the first iteration's observations
  std::size_t start_correspondences = 0;  ///< observations of the first iteration
  Vector7d start = Vector7d::Zero();      ///< parameters at the initial guess (reduced frame)
  Vector7d estimate = Vector7d::Zero();   ///< final parameters
  Eigen::AlignedBox3d source_box;         ///< of the reduced source points
  Matrix7d covariance = Matrix7d::Zero();  ///< of the estimate (AdjustmentReport::covariance)
};

/// The figures of QualityFigures from the last observation set (distinct observed points).
QualityFigures
measureQuality(const QualityInputs& in, const ObservationSet& observations);

/// For a rule with several observations per point: √(Σ w l² / Σ w) over the first observation
/// of each point (component 0: across the surface; l / |u|, a distance for every rule), with
/// the estimator's weights `w` (one per observation). 0 when every observation is a point's
/// only one (LND, LZD: σ0 measures that already) or no weight is positive.
double
normalComponentSigma(const ObservationSet& observations, const Eigen::VectorXd& weights);

/// The data fix the source's position far worse than the surfaces' noise (position_sigma above
/// max_position_sigma_ratio × it) and the move lies within that uncertainty: the gate's "the
/// data do not determine the move" (nearly flat terrain for rotations and horizontal shifts).
bool
moveUndetermined(const QualityFigures& q, const AdjustmentSettings& settings);

/// A rigid fit's held-out scale is significant (|z| > held_out_z) and moves the source's edge by
/// more than held_out_noise_factor × the surfaces' noise: the model is too small.
bool
heldOutScaleFlagged(const QualityFigures& q, const AdjustmentSettings& settings);

/// Applies the settings' limits to a finished adjustment (CONVERGED or MAX_ITERATIONS):
/// returns its termination, or STALLED / UNRELIABLE / IMPLAUSIBLE_SCALE with the reasons
/// appended to `why`; sets q.trustworthy.
TerminationType
applyQualityGate(QualityFigures& q, const QualityInputs& in, bool scale_estimated,
                 const AdjustmentSettings& settings, TerminationType termination, std::string& why);

}  // namespace pcl_ls3d
