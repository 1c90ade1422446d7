#pragma once
/// \file strip_adjustment_settings.h
/// \brief Every knob of the strip block adjustment in one plain struct with in-class defaults
///        and isValid() (the AdjustmentSettings style). Lengths are in the unit of the data.

#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/adjustment/parameter_block.h>
#include <pcl_ls3d/estimators/robust_estimator.h>
#include <pcl_ls3d/rules/conjugate_rule.h>

#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace strips {

/// \brief Settings of StripBlockAdjustment.
struct StripAdjustmentSettings
{
  // --- overlaps (footprints on a raster) -----------------------------------------------------
  /// Footprint cell edge; 0 = 3 / √(density of the sparsest strip), ≈ 9 points per cell.
  double footprint_cell = 0.0;
  /// Overlaps with a smaller common area are skipped (listed with the reason); 0 = 100 cells.
  double min_overlap_area = 0.0;
  /// A direction of an overlap with fewer observed points (after thinning) is not matched: a
  /// sliver of overlap would weigh two strips' parameters with a handful of points.
  std::size_t min_overlap_observations = 100;

  // --- observations ----------------------------------------------------------------------------
  /// Stable surfaces by class when a strip is classified (ground, building); vegetation, water,
  /// noise and everything else are left out.
  std::set<std::uint8_t> stable_classes = {2, 6};
  /// Unclassified strips: a point is on a stable surface when the RMS distance of its 10
  /// nearest neighbours to their plane is below this many times the median over the overlap.
  double roughness_factor = 2.5;
  /// Regular thinning of the observed points: one per square cell of this edge; 0 = automatic
  /// (2 × the point spacing, widened so an overlap direction gives at most max_observations).
  double observation_spacing = 0.0;
  std::size_t max_observations = 60000;  ///< per overlap and direction (automatic spacing)
  /// Source points of strip i are observed on strip j's surface and vice versa; false: only
  /// strip i's points on strip j, half the matching.
  bool both_directions = true;

  // --- model -------------------------------------------------------------------------------------
  ParameterModel model = ParameterModel::RIGID_6;  ///< per strip: 7, 6, 3 or height only
  ConjugateRuleType rule = ConjugateRuleType::LND;
  RobustEstimatorChoice estimator;  ///< Zuo's 0/1 weight at 6 σ0 by default
  /// Conjugate points farther than this are none (also the reach of the overlap culling).
  double max_distance = 10.0;

  // --- datum ---------------------------------------------------------------------------------------
  /// Reference strips (indices into the strip list), fixed by infinite a-priori weight. Empty:
  /// in each connected part of the overlap graph the strip with the largest overlap area.
  std::vector<int> reference_strips;
  /// Soft datum instead (Zuo eqs. 9–10 per strip): every strip observed at the identity with
  /// these a-priori σ (tx ty tz [length], φ ω κ [rad], m); weights σ_obs² / σ_e², σ_obs from
  /// the first iteration's robust scale. No strip is fixed.
  bool soft_datum = false;
  Vector7d soft_sigmas = (Vector7d() << 0.5, 0.5, 0.5, 1e-3, 1e-3, 1e-3, 1e-4).finished();

  // --- iterations, determinability, precision: the pair engine's settings ------------------------
  /// The block iterates as a pair does (advancePhase(), iteration_control.h) and reads these
  /// fields of the engine's settings: max_iterations, angle_epsilon, translation_epsilon,
  /// scale_epsilon, freeze_sigma_fraction, coarse_observations, determinability_threshold,
  /// spatial_precision, precision_cell (0 = 8 × the observation spacing), held_out_z and
  /// held_out_noise_factor (the model adequacy test below). The rest is the pair engine's
  /// alone. Two defaults differ from a pair's: see blockAdjustmentDefaults().
  AdjustmentSettings adjustment = blockAdjustmentDefaults();

  /// The engine's defaults with the two a block changes:
  ///  - translation_epsilon 1e-4 (a pair: 1e-5): a block stops only when every strip's change
  ///    is below it, and a tenth of a millimetre is far below airborne strips' noise;
  ///  - coarse_observations 15 000 (a pair: 200 000): a block counts them per overlap direction,
  ///    and a block has many overlaps, each of which needs only a settled estimate from them.
  static AdjustmentSettings
  blockAdjustmentDefaults();

  // --- model adequacy (model_adequacy.h) -------------------------------------------------------
  /// After a rigid adjustment (-params 6), test each strip's held-out scale: a score test from
  /// the overlaps' normal equations at the final pose, with the sandwich's variance.
  bool test_held_out = true;
  /// Its thresholds are the engine's (adjustment.held_out_z, default 5, and
  /// adjustment.held_out_noise_factor, default 1, applied to each strip's own noise and its
  /// effect |m − 1| × the strip's radius). 5, not 3: on some generated rigid blocks the
  /// observations carry a scale-like systematic of 3–5 σ (docs/MODEL_ADEQUACY.md).

  bool
  isValid(std::string* why = nullptr) const;
};

}  // namespace strips
}  // namespace pcl_ls3d
