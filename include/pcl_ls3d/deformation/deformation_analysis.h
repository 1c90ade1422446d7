#pragma once
/// \file deformation_analysis.h
/// \brief Local deformation between two epochs in one call (Li et al. 2001): robust matching of
///        the epoch onto the reference (estimators/robust_matching.h), the residual field with σ
///        and significance (residual_field.h), and connected regions with area, displacement and
///        volume (deformation_regions.h), the stable part matched again without the regions
///        (stable_refinement.h). PCL-free: pcl_ls3d_deformation loads the clouds and calls it.

#include <pcl_ls3d/deformation/deformation_regions.h>
#include <pcl_ls3d/deformation/residual_field.h>
#include <pcl_ls3d/deformation/stable_refinement.h>
#include <pcl_ls3d/deformation/start_choice.h>
#include <pcl_ls3d/estimators/robust_matching.h>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace deformation {

/// \brief Everything the analysis can be told.
struct DeformationSettings
{
  /// Estimator and adjustment (default: MM, LZD-style 6 parameters; see docs/BENCHMARKS.md).
  RobustMatchingSettings matching = defaultMatching();
  ConjugateRuleType rule = ConjugateRuleType::LZD;  ///< LHD (Li et al.) = LZD + 6 parameters
  ResidualSettings residuals;
  RegionSettings regions;
  /// After the robust matching: the deformed regions left out, the stable part matched again
  /// (stable_refinement.h). max_rounds = 0 gives the estimator's own answer (Li's tables).
  StableRefinementSettings refinement;
  /// The robust matching uses at most this many epoch points (a random sample with a fixed
  /// seed: it covers the surface evenly without aliasing a grid or scan lines); the residual
  /// field is always computed for every point.
  /// The transformation's σ are those of the sample. 0: all points.
  std::size_t matching_points = 50000;
  /// When the data do not determine a rotating model's fit (the quality gate's "the data do not
  /// determine the move": nearly flat terrain fixes heights and tilts only weakly in plan), the
  /// analysis is run again with the translation alone, and says so (DeformationResult::
  /// model_note). Epochs in one georeferenced frame differ mostly by a shift.
  bool translation_when_undetermined = true;
  /// The final fit is UNRELIABLE when the scatter of its stable part (1.4826 · med |r| of the
  /// observed points outside the deformed regions) exceeds this multiple of σ_d, the noise of
  /// neighbouring residuals of the same field (neighbour_noise.h). At the truth the stable part
  /// is the noise and the ratio ≈ 1; a fit that compromises between the stable and the moved
  /// part leaves a tilted stable part, which σ_d (differences of neighbours) does not see.
  /// On Li's 50 × 50 grid no successful LMS or MM trial exceeded 1.04, while every one ending
  /// more than 2 σ off but one exceeded 1.10 (docs/HONESTY_API.md). Off (0) by default: on
  /// denser surfaces σ_d is not the noise (neighbouring residuals share the reference's local
  /// surface: σ_d 13 for σ = 20 at 5–8-unit spacing), and right fits there reach 1.25–1.9.
  /// Set e.g. 1.10 for surfaces sampled no denser than their noise's correlation length. Not
  /// applied to the translation-only fallback (translation_when_undetermined), whose stable
  /// part keeps the trace of the tilts it cannot follow.
  double max_stable_scatter_ratio = 0.0;

  static RobustMatchingSettings
  defaultMatching()
  {
    RobustMatchingSettings s;
    s.method = RobustMethod::MM;
    s.block_start = true;  // the second start the analysis chooses from (start_choice.h)
    return s;
  }
  bool
  isValid(std::string* why = nullptr) const;
};

/// \brief The analysis' result: the matching (transformation EPOCH → REFERENCE, σ, σ̂, weights,
///        subsets, why it stopped), the residual field and its regions (epoch order).
struct DeformationResult
{
  RobustMatchingReport matching;
  StableRefinementReport refinement;
  StartChoice start_choice;  ///< LMS / MM: the fits from their starts that competed (start_choice.h)
  ResidualField field;
  RegionAnalysis regions;
  /// Why the parameters are fewer than asked ("" when they are not): the rotating fit the data
  /// did not determine (DeformationSettings::translation_when_undetermined).
  std::string model_note;
  /// The stable part's scatter and σ_d of the final field (DeformationSettings::
  /// max_stable_scatter_ratio); 0: not measured.
  double stable_scatter = 0.0;
  double field_noise = 0.0;
  /// True when the matching gave a usable estimate and the field was computed.
  bool
  ok() const
  {
    return matching.isSolutionUsable();
  }
};

/// The model of the fallback (DeformationSettings::translation_when_undetermined): the
/// rotations and the scale fixed at the guess, the translations as \a settings have them (free,
/// soft or fixed).
AdjustmentSettings
translationAlone(const AdjustmentSettings& settings);

/// True when \a r failed because the data do not determine where the rotating model of
/// \a adjustment puts the epoch (the quality gate's moveUndetermined()): what the fallback acts on.
bool
rotationsUndetermined(const DeformationResult& r, const AdjustmentSettings& adjustment);

/// Robust matching of `epoch` onto `reference`, then the residual field and its regions.
/// \param[in] epoch points in the epoch's own coordinates (NaN allowed: no residual)
/// \param[in] rule prepared on `reference`
/// \param[in] guess EPOCH → REFERENCE start (4×4)
DeformationResult
analyseDeformation(const std::vector<Eigen::Vector3d>& epoch, const TargetSurface& reference,
                   const ConjugateRule& rule, const DeformationSettings& settings,
                   const Eigen::Matrix4d& guess = Eigen::Matrix4d::Identity());

}  // namespace deformation
}  // namespace pcl_ls3d
