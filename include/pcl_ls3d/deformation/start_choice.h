#pragma once
/// \file start_choice.h
/// \brief The choice between the starts of MM and LMS (beyond Li et al. 2001). Three fits
///        compete: the estimator's own (MM: LTS start and Tukey M-step; LMS: Li's subset fit
///        and M-step) refined on its stable part, and its subset start and the block start
///        (sample_consensus/block_trimmed_squares.h), each matched on the observed points
///        outside its own deformed regions (on all points when the regions' significant points
///        are half of the observed or more) and refined the same way. Each fails where
///        another holds (docs/DECISIONS.md): a large, strong patch walks the M-step from a good
///        start to a compromise, and on a weaker one the point-wise LTS optimum itself is a
///        compromise that the block start is not.
///
/// The score is the same for every fit, and none of the fits' own scales (a compromise
/// inflates its own): the residuals at the fit are tested at σ_d, the noise of neighbouring
/// residuals (estimators/neighbour_noise.h), the deformed regions found as the user's are, and
/// the score is 1.4826 · med |r| of the observed points outside them — infinite when the
/// regions' significant points are half of the observed or more (the points the hysteresis
/// grew in are not counted: near half deformed the patch's rim would tip a right fit over half).
/// The estimator's own fit also competes when the quality gate refused it (it scores
/// infinite), and a compromise scores well above the noise where the stable part's own fit
/// scores about σ. A fit replaces the one kept so far only when it scores smaller by more than
/// the standard error of a MAD scale from n points, 1.166 / √n (Hampel et al. 1986), so that
/// fits which agree keep the estimator's own. PCL-free.

#include <pcl_ls3d/deformation/deformation_regions.h>
#include <pcl_ls3d/deformation/residual_field.h>
#include <pcl_ls3d/deformation/stable_refinement.h>
#include <pcl_ls3d/estimators/robust_matching.h>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace deformation {

/// \brief The scatter of the stable part at `fit` (see the file comment); +inf when the
///        regions' significant points are half of the observed ones or more.
/// \param[in] noise the scale the residuals are tested at (σ_d)
/// \param[out] outside (optional) the observed points outside the regions
double
stablePartScatter(const std::vector<Eigen::Vector3d>& points, const TargetSurface& reference,
                  const ConjugateRule& rule, const AdjustmentReport& fit, double noise,
                  const ResidualSettings& residuals, const RegionSettings& regions,
                  std::size_t* outside = nullptr);

/// \brief One competing fit and its score.
struct StartCandidate
{
  std::string name;         ///< "mm" / "lms" (the estimator's fit), "lts start" / "lms start", "block start"
  double scatter = 0.0;     ///< stablePartScatter() after its refinement (inf: not scored)
  std::size_t outside = 0;  ///< the points it was measured on
  bool usable = false;      ///< its matching gave an estimate and its refinement settled (CONVERGED)
};

/// \brief What chooseBetweenStarts() compared and kept.
struct StartChoice
{
  std::vector<StartCandidate> candidates;  ///< empty: no choice made (not LMS / MM, or no block start)
  std::string chosen;                      ///< the name of the fit kept (the first candidate's: none changed)
  std::string chosen_matching;             ///< a start's fit: its first matching (before the refinement)
};

/// \brief Replaces `robust` / `refinement` (the LMS / MM estimate refined on its stable part) by
///        the refined fit from its subset start or the block start when that scores clearly
///        smaller — also when the quality gate refused `robust` (it then scores infinite).
/// \param[in] unrefined the robust matching before its refinement (its starts and σ_d)
StartChoice
chooseBetweenStarts(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& point_indices,
                    const TargetSurface& reference, const ConjugateRule& rule,
                    const RobustMatchingSettings& matching, const ResidualSettings& residuals,
                    const RegionSettings& regions, const StableRefinementSettings& settings,
                    const RobustMatchingReport& unrefined, RobustMatchingReport& robust,
                    StableRefinementReport& refinement);

}  // namespace deformation
}  // namespace pcl_ls3d
