#pragma once
/// \file adjustment_report.h
/// \brief The plain result of one LS3D adjustment (Ceres `Summary` / small_gicp
///        `RegistrationResult` style): estimate, precision (Zuo et al. 2012, eqs. 11, 14),
///        reliability (redundancy numbers), why it stopped, and a per-iteration log.

#include <pcl_ls3d/common/similarity_transform.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace pcl_ls3d {

/// \brief Why the adjustment stopped.
enum class TerminationType
{
  NOT_RUN,               ///< no adjustment has been run yet
  CONVERGED,             ///< parameter changes fell below the epsilons
  MAX_ITERATIONS,        ///< iteration limit reached before convergence
  INVALID_INPUT,         ///< empty / NaN-only clouds, invalid settings
  NO_OVERLAP,            ///< no source observation lies over the target surface
  TOO_FEW_OBSERVATIONS,  ///< fewer usable observations than settings.min_observations
  SINGULAR,              ///< no free parameter could be determined / solve failed
  DIVERGED,              ///< estimate became non-finite
  STALLED,               ///< stopped at the initial guess with a fit the data contradict (quality_gate.h)
  UNRELIABLE,            ///< stopped, but the fit fails the quality gate: not trustworthy (quality_gate.h)
  IMPLAUSIBLE_SCALE      ///< the estimated scale is beyond settings.max_scale_deviation
};

/// "CONVERGED", "MAX_ITERATIONS", ...
const char*
terminationTypeToString(TerminationType type);

/// \brief One line of the iteration log.
struct IterationRecord
{
  int iteration = 0;
  std::size_t observations_used = 0;       ///< observations with non-zero weight
  std::size_t observations_rejected = 0;   ///< correspondences given weight 0 by the estimator
  double sigma0 = 0.0;                     ///< σ̂0 of this iteration's solve (eq. 11)
  double max_angle_change = 0.0;           ///< [rad] max |dφ|, |dω|, |dκ|
  double translation_change = 0.0;         ///< [length] |dt|
  double scale_change = 0.0;               ///< |dm|
  Vector7d parameters = Vector7d::Zero();  ///< estimate after this iteration (reduced frame)
  bool extrapolated = false;               ///< the step was extrapolated (settings.accelerate)
};

/// \brief How far the result can be trusted: the figures of the quality gate (quality_gate.h).
struct QualityFigures
{
  /// √(σ_s² + σ_t²): the noise the two surfaces carry (local quadric roughness of each; 0: unknown).
  double expected_noise = 0.0;
  double source_noise = 0.0;  ///< σ_s of the source (its own local roughness)
  double target_noise = 0.0;  ///< σ_t of the target near the conjugate points
  /// What σ0 is compared with: expected_noise, but at least 1e-3 × the target's point spacing
  /// (noise-free data would make any σ0 infinitely many times its noise).
  double noise_yardstick = 0.0;
  double sigma0_ratio = 0.0;  ///< σ0 / noise_yardstick (≈ 1 for a good fit; 0: unknown)
  /// Rules with several observations per point (ICP: the normal and two down-weighted
  /// tangents): the weighted RMS of the first observation of each point (the one across the
  /// surface) / noise_yardstick. σ0 averages it with the tangents, which carry the sampling
  /// offset of the closest point and no misfit. 0: single-observation rule (σ0 is that).
  double normal_sigma_ratio = 0.0;
  /// Source points over the target's extent that have an observation, as a fraction of them.
  double coverage = 0.0;
  double rejected_fraction = 0.0;  ///< correspondences the estimator gave weight 0, as a fraction
  /// Median |u| of the observations' gradients: 1 for distance rules (LND, ICP); for LZD
  /// 1 / cos(slope), so above √2 most observations lie on surfaces steeper than 45°, where a
  /// vertical difference is no surface distance.
  double median_gradient = 1.0;
  double movement =
      0.0;  ///< largest displacement of the estimate from the initial guess over the source's extent
  /// Largest 1σ uncertainty of where the estimate puts a corner of the source's box (the
  /// reported covariance propagated, along the worst direction): how well the data fix the
  /// source's position. Far above the surfaces' noise the estimate is not determined by the data.
  double position_sigma = 0.0;
  /// 1.4826 · median |l| of the correspondences at the initial guess and at the end: a fit that
  /// ends worse than it started moved away from the data.
  double start_scale = 0.0;
  double final_scale = 0.0;
  /// Correspondences at the end as a fraction of those at the initial guess: far below 1 the
  /// source slid off the overlap until what is left of it fits.
  double observations_kept = 1.0;
  /// A rigid fit's held-out scale, as it would be if freed (omitted_parameters.h): the change
  /// m − m0 it would take (one Gauss–Newton step), its σ with the sandwich's variance, z = Δm / σ
  /// and how far it moves the source's edge (|Δm| × the source's radius). Not tested when the
  /// scale was estimated or other parameters were held too.
  bool held_out_scale_tested = false;
  double held_out_scale = 0.0, held_out_scale_sigma = 0.0, held_out_scale_z = 0.0;
  double held_out_scale_effect = 0.0;
  bool trustworthy = false;  ///< every figure within the settings' limits
};

/// \brief Everything one adjustment produced. Parameter order: tx, ty, tz, φ, ω, κ, m.
struct AdjustmentReport
{
  TerminationType termination = TerminationType::NOT_RUN;
  std::string message;  ///< human-readable reason / warnings
  int iterations = 0;

  /// X̂ in the reduced frame: x_t − o_t = t + m R (x_s − o_s) (eq. 2 on reduced coordinates).
  Vector7d parameters = (Vector7d() << 0, 0, 0, 0, 0, 0, 1).finished();
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();   ///< same, in cloud coordinates
  Eigen::Vector3d local_origin_source = Eigen::Vector3d::Zero();  ///< o_s (cloud coordinates)
  Eigen::Vector3d local_origin_target = Eigen::Vector3d::Zero();  ///< o_t = guess(o_s)

  double sigma0 = 0.0;  ///< σ̂0 = sqrt((VᵀPV + V_eᵀP_eV_e) / r), eq. 11
  /// σ_i = √C_ii of the reported covariance; 0 fixed, +inf undeterminable.
  Vector7d sigmas = Vector7d::Zero();
  /// Formal σ0 √q_ii (eq. 14), which assumes independent observations (too small when
  /// observations share target points; kept for comparison with the paper).
  Vector7d sigmas_formal = Vector7d::Zero();
  /// Covariance of X̂ behind `sigmas`: the spatial sandwich (settings.spatial_precision) or
  /// σ0² Qxx; zero rows for held parameters.
  Matrix7d covariance = Matrix7d::Zero();
  /// "spatial sandwich (cell h m)" or "formal (eq. 14)".
  std::string precision_model;
  double source_noise = 0.0;        ///< σ_s estimated for the errors-in-variables correction (0: not used)
  Matrix7d qxx = Matrix7d::Zero();  ///< cofactor matrix (AᵀPA + P_e)⁻¹, zero for held parameters
  Matrix7d correlation = Matrix7d::Zero();  ///< ρ_ij = C_ij / √(C_ii C_jj); zero rows for held parameters
  std::array<bool, 7> fixed{};              ///< infinite a-priori weight
  std::array<bool, 7> determinable{};       ///< free and resolvable by the geometry (rank test)
  long redundancy = 0;                      ///< r = n − u (eq. 11), including soft a-priori observations

  std::size_t source_points = 0;          ///< valid source points used as candidate observations
  std::size_t correspondences = 0;        ///< observations for which the rule found a conjugate point
  std::size_t observations_used = 0;      ///< with non-zero weight in the last iteration
  std::size_t observations_rejected = 0;  ///< zero weight from the robust estimator (eq. 15)

  /// Per observation of the last iteration (settings.store_observations): source point index,
  /// residual v_i, weight p_i, redundancy number r_i = 1 − p_i a_iᵀ Qxx a_i.
  std::vector<int> observation_source_index;
  std::vector<double> residuals;
  std::vector<double> weights;
  std::vector<double> redundancy_numbers;

  QualityFigures quality;  ///< the quality gate's figures (after a run that produced an estimate)

  std::vector<IterationRecord> log;  ///< one record per iteration
  std::string rule_name;             ///< conjugate-point rule used
  std::string estimator_name;        ///< robust estimator used

  /// Parameters as a SimilarityTransform (reduced frame).
  SimilarityTransform
  similarity() const
  {
    return SimilarityTransform(parameters);
  }
  /// True when the estimate can be used: converged (or hit the iteration limit) with finite
  /// values and passed the quality gate.
  bool
  isSolutionUsable() const;
  /// True when an estimate exists even though it may not be trusted (STALLED, UNRELIABLE,
  /// IMPLAUSIBLE_SCALE keep it in `parameters` / `transformation` for inspection).
  bool
  hasEstimate() const;
  /// One line: termination, iterations, σ0, observations.
  std::string
  brief() const;
  /// Multi-line human-readable report (parameters ± σ, correlation matrix, origins, log).
  std::string
  fullReport() const;
};

}  // namespace pcl_ls3d
