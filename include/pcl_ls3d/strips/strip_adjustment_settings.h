#pragma once
/// \file strip_adjustment_settings.h
/// \brief Every knob of the strip block adjustment in one plain struct with in-class defaults
///        and isValid() (the AdjustmentSettings style). Lengths are in the unit of the data.

#include <pcl_ls3d/adjustment/parameter_block.h>
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
  std::string estimator = "zuo";                   ///< parseRobustEstimator() text
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

  // --- iterations (Zuo §4) ---------------------------------------------------------------------------
  int max_iterations = 30;
  double angle_epsilon = 1e-6;        ///< [rad]
  double translation_epsilon = 1e-4;  ///< [length]
  double scale_epsilon = 1e-8;
  /// Correspondences are frozen once every change is below this fraction of its σ.
  double freeze_sigma_fraction = 0.1;
  /// While far from the solution, each overlap direction observes about this many points.
  std::size_t coarse_observations = 15000;
  double determinability_threshold = 1e-7;

  // --- precision ------------------------------------------------------------------------------------
  bool spatial_precision = true;  ///< spatial sandwich (spatial_precision.h) instead of eq. 14
  double precision_cell = 0.0;    ///< 0 = 8 × the observation spacing

  // --- model adequacy (model_adequacy.h) -------------------------------------------------------
  /// After a rigid adjustment (-params 6), test each strip's held-out scale: a score test from
  /// the overlaps' normal equations at the final pose, with the sandwich's variance.
  bool test_held_out = true;
  /// A held-out parameter is significant when |estimate| > held_out_z × its σ. 5, not 3: on
  /// some generated rigid blocks the observations carry a scale-like systematic of 3–5 σ (chosen
  /// on seeds 1–10 of benchmark_strip_block -honesty, docs/MODEL_ADEQUACY.md).
  double held_out_z = 5.0;
  /// ... and it makes the result NOT CONFIRMED when its effect over the strip's extent
  /// (|m − 1| × the strip's radius) also exceeds this multiple of the strip's own noise.
  double held_out_noise_factor = 1.0;

  bool
  isValid(std::string* why = nullptr) const;
};

/// "7", "6", "3", "z" (or "1") → model; false when unknown.
bool
parseParameterModel(const std::string& text, ParameterModel& model);
/// "7", "6", "3", "z".
std::string
parameterModelName(ParameterModel model);

}  // namespace strips
}  // namespace pcl_ls3d
