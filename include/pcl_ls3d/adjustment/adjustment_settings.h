#pragma once
/// \file adjustment_settings.h
/// \brief Every knob of the LS3D Gauss–Markoff adjustment in one plain struct (Ceres `Options`
///        style): in-class defaults, named presets, and isValid() for tools and setters.

#include <pcl_ls3d/adjustment/parameter_block.h>

#include <cstddef>
#include <limits>
#include <string>

namespace pcl_ls3d {

/// True for a correspondence distance that means "unlimited": pcl::Registration's default
/// √DBL_MAX and anything larger (infinity, DBL_MAX).
inline bool
isUnlimitedDistance(double distance)
{
  return !(distance < 1.3407807929942596e154);  // √DBL_MAX
}

/// \brief Settings of the adjustment. Units: lengths in the unit of the data, angles [rad].
///
/// A-priori parameter observations (Zuo et al. 2012, eq. 9): V_e = X − L_e with weight P_e.
/// A weight is relative to a unit-weight observation (P_e = σ0² / σ_e²): 0 = free,
/// +infinity = fixed (the column is eliminated, the parameter stays exactly at its a-priori
/// value), anything in between = soft constraint.
///
/// Parameters refer to the transform in the reduced frame: x_t − o_t = t + m R (x_s − o_s),
/// with o_s the centroid of the source observations and o_t its image under the initial guess
/// (both reported); the final 4×4 matrix is given in the clouds' own coordinates.
struct AdjustmentSettings
{
  // --- a-priori parameter observations (eq. 9) ---------------------------------------------
  /// P_e per parameter: 0 free, +inf fixed, otherwise a soft constraint. Default: rigid (the
  /// scale fixed at the guess's), as the ICP this class replaces; setParameterModel(SIMILARITY_7)
  /// or -params 7 frees it.
  Vector7d apriori_weights = parameterModelWeights(ParameterModel::RIGID_6);
  /// L_e per parameter (reduced frame). Used when apriori_from_guess is false.
  Vector7d apriori_values = (Vector7d() << 0, 0, 0, 0, 0, 0, 1).finished();
  /// When true (default), L_e is the initial guess expressed in the reduced frame, so fixed
  /// parameters keep the guess's value (identity guess: t = 0, angles = 0, m = 1).
  bool apriori_from_guess = true;

  // --- iteration and convergence (Zuo §4: angle change < 1e-6 rad, < ~20 iterations) --------
  int max_iterations = 30;            ///< upper bound on Gauss–Newton iterations
  double angle_epsilon = 1e-6;        ///< [rad] converged when every |dφ|,|dω|,|dκ| below
  double translation_epsilon = 1e-5;  ///< [length] ... and |dt| below
  double scale_epsilon = 1e-8;        ///< [-] ... and |dm| below

  /// Conjugate points are searched afresh every iteration until every parameter change is
  /// below this fraction of its σ_i; from then on they are frozen (the rules' per-point caches
  /// are kept), so the final iterations converge to the epsilons instead of cycling between
  /// neighbouring triangles. Freezing earlier would bias the estimate towards the initial guess
  /// (triangles chosen around the wrong positions).
  double freeze_sigma_fraction = 0.1;

  /// Besl & McKay's acceleration: when consecutive steps are nearly parallel and shrink by a
  /// steady ratio ρ (0.3 < ρ < 0.97; the creep of closest-point rules), jump to the limit of the
  /// geometric series (at most 10 steps ahead). LND/LZD steps shrink faster and are unaffected.
  bool accelerate = true;

  /// Coarse-to-fine for big clouds: while the estimate is still far off (changes above 1 σ_i),
  /// iterate on every k-th source point only, k chosen so that about this many are used; then
  /// continue on all points (and finally freeze). 0 = always use every point.
  std::size_t coarse_observations = 200000;

  /// With an unlimited max_correspondence_distance (no overlap grid, see overlap_grid.h), a
  /// source point that found no correspondence is searched again only every recheck_interval-th
  /// iteration (a point outside the overlap costs one search in that many); 0 or 1 = every
  /// iteration. Frozen iterations reuse the rules' caches and need no search anyway.
  int recheck_interval = 3;

  // --- observations --------------------------------------------------------------------------
  /// Conjugate points farther than this (|signed distance| and nearest target point) are no
  /// correspondence. Default: unlimited, as in pcl::Registration — but see automatic_reach.
  double max_correspondence_distance = std::numeric_limits<double>::max();
  /// With an unlimited max_correspondence_distance, derive the reach from the data: unlimited
  /// in the first iteration, then max(4 s, 6 σ0 + 2 s) with s the target's point spacing and σ0
  /// of the previous iteration. Far points (below a bridge, across a river, beyond the overlap)
  /// then stop pulling once the estimate has settled, and the overlap grid culls them. False:
  /// truly unlimited.
  bool automatic_reach = true;
  /// How far the initial guess may be off [length]. Observations with |v| up to this are kept in
  /// the first iteration whatever the estimator's own cut says, and that floor halves every
  /// iteration (an annealed cut): where most points already agree with the guess and only a
  /// few see its error (street scans offset along the street: only poles, trunks and car fronts
  /// see it), the estimator's first scale comes from the agreeing majority and would cut those
  /// few. 0 (default): 1 % of the source's bounding-box diagonal, at most the
  /// max_correspondence_distance. Used by estimators that cut (ZuoEstimator).
  double guess_uncertainty = 0.0;
  /// Regular thinning of the source observations: one source point per voxel of this edge
  /// [length]; 0 = use every source point.
  double source_thinning = 0.0;
  /// Fewer observations than this (after rejection) stop the adjustment as a failure.
  int min_observations = 20;

  // --- determinability -------------------------------------------------------------------------
  /// A free parameter is undeterminable when the reduced normal matrix, scaled so every column
  /// is "displacement at the source extent", has an eigenvalue below this fraction of the
  /// largest one along that parameter (rank test). It is then held at its current value.
  double determinability_threshold = 1e-7;

  // --- precision (see spatial_precision.h) --------------------------------------------------
  /// Report σ_i from the sandwich covariance Q (AᵀP Σ_ll P A) Q with a spatial HAC estimate of
  /// the middle term (observations sharing target points are correlated), instead of the
  /// formal σ0 √q_ii of eq. 14 (kept as AdjustmentReport::sigmas_formal).
  bool spatial_precision = true;
  /// Cell edge h of the spatial HAC estimator [length]; 0 = automatic (8 × the target's mean
  /// XY point spacing, i.e. well beyond the neighbourhoods the rules fit).
  double precision_cell = 0.0;
  /// Errors in variables: the source coordinates are noisy and enter the scale column of the
  /// design matrix (a_m = uᵀ R x), correlating it with the observation l and biasing m by
  /// about −σ_s² / mean((uᵀRx)²). When true the column is evaluated at the adjusted source point
  /// (Gauss–Helmert linearisation point), x − c l R⁻¹u/m, which removes the correlation; the
  /// source noise σ_s is estimated from the source's own local quadric residuals.
  bool correct_source_noise = true;

  // --- quality gate (quality_gate.h): when a result is not to be trusted -------------------------
  /// With the scale estimated, |m − 1| beyond this fails the adjustment (IMPLAUSIBLE_SCALE).
  /// 0.5 % = 5 mm per metre: scans and strips differ by ppm, a collapsing scale by far more.
  double max_scale_deviation = 0.005;
  /// σ0 beyond this multiple of the noise both surfaces carry (their own local roughness)
  /// marks the result not trustworthy: good fits end well below it (docs/DECISIONS.md).
  double max_sigma0_ratio = 3.0;
  /// Fewer source points over the target's extent with an observation than this fraction of
  /// them marks the result not trustworthy (a fit held by a small part of the overlap).
  double min_coverage = 0.1;
  /// More correspondences rejected by the robust estimator than this fraction marks the
  /// result not trustworthy (good fits reject a few per cent; a collapsed σ0 far more).
  double max_rejected_fraction = 0.25;
  /// A median observation gradient |u| above this marks the rule unsuitable for the surface
  /// (LZD, a vertical difference, on mostly steep surfaces). Off by default, because the slope
  /// does not tell a valid LZD on a steep height field from a failing one on a closed object
  /// (docs/DECISIONS.md); set e.g. 1.3 when LZD is used on objects rather than terrain.
  double max_median_gradient = std::numeric_limits<double>::infinity();
  /// The robust scale of the residuals (1.4826 · median |l|) at the end above this multiple of
  /// the one at the initial guess, or of the surfaces' own noise when that is larger: the
  /// adjustment moved away from the data.
  double max_scale_growth = 1.25;
  /// Fewer correspondences at the end than this fraction of those at the initial guess: the
  /// source slid off the overlap until what is left of it fits, which σ0 alone does not show
  /// (docs/DECISIONS.md). 0: off.
  double min_observations_kept = 0.5;
  /// A fit whose position σ (QualityFigures::position_sigma) exceeds max_position_sigma_ratio ×
  /// the surfaces' noise and that moved the source by more than the noise but by less than
  /// min_movement_significance × that σ made a move the data do not support: a sparse or narrow
  /// overlap lets the estimate wander metres with σ of metres (docs/DECISIONS.md).
  double max_position_sigma_ratio = 2.0;
  double min_movement_significance = 3.0;
  /// A rigid fit whose held-out scale (QualityFigures::held_out_scale) is beyond held_out_z × its
  /// σ and moves the source's edge by more than held_out_noise_factor × the surfaces' noise is not
  /// trustworthy: the data ask for a scale (free it, -params 7). +inf switches the test off.
  double held_out_z = 5.0;  ///< as the strip adjustment's (docs/MODEL_ADEQUACY.md)
  double held_out_noise_factor = 1.0;

  // --- results ----------------------------------------------------------------------------------
  /// Keep per-observation residuals, weights and redundancy numbers r_i in the report
  /// (needed by Baarda's test; 3 doubles per observation).
  bool store_observations = true;

  /// Fixes (infinite weight) or frees (zero weight) one parameter.
  void
  fixParameter(int index, bool fixed = true);
  /// True when parameter `index` has infinite a-priori weight.
  bool
  isFixed(int index) const;
  /// Applies a preset: frees the model's parameters, fixes the rest (soft weights are lost).
  void
  setParameterModel(ParameterModel model);

  /// Named presets (defaults otherwise).
  static AdjustmentSettings
  similarity7();
  static AdjustmentSettings
  rigid6();
  static AdjustmentSettings
  translationOnly();
  static AdjustmentSettings
  heightOnly();

  /// True when the settings can be used; otherwise `why` (if given) says which field is wrong.
  bool
  isValid(std::string* why = nullptr) const;
};

/// \brief The source body of a pair reduced about \a reduction_origin (o_s), with the output
///        origin o_t = guess(o_s): starting values from the guess (eq. 9's L_e when
///        apriori_from_guess; translations 0, since o_t is the image of o_s), the a-priori values
///        and weights of \a settings, and every fixed parameter exactly at its a-priori value.
///        The LS3D pair engine and LinearizedMatching (robust matching) start from it alike.
ParameterBlock
sourceBlockFromGuess(const Eigen::Matrix4d& guess, const Eigen::Vector3d& reduction_origin,
                     const AdjustmentSettings& settings);

}  // namespace pcl_ls3d
