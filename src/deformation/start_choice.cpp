#include <pcl_ls3d/adjustment/observation_weighting.h>
#include <pcl_ls3d/common/similarity_transform.h>
#include <pcl_ls3d/deformation/start_choice.h>

#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace deformation {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// √n × the relative standard error of 1.4826 · MAD for normal errors (Hampel et al. 1986).
constexpr double kMadStandardError = 1.166;

// The adjustment record of `like` moved to the transformation T (parameters in its reduced
// frame; no covariance: the field's σ then come from the noise alone).
AdjustmentReport
fitAt(const AdjustmentReport& like, const Eigen::Matrix4d& T)
{
  AdjustmentReport at = like;
  at.transformation = T;
  const Eigen::Matrix4d local = globalToLocal(T, like.local_origin_source, like.local_origin_target);
  at.parameters = SimilarityTransform::fromMatrix(local).vector();
  at.covariance.setZero();
  return at;
}

// Whether the significant points of T's regions are fewer than half of the observed ones. The
// points the hysteresis grew in are not counted: at 49 % deformed the patch's rim of 2 σ noise
// would tip a right fit over half.
bool
significantMinority(const ResidualField& field, const RegionAnalysis& analysis)
{
  std::size_t cores = 0;
  for (std::size_t i = 0; i < analysis.region.size(); ++i)
    cores += analysis.region[i] > 0 && field.significant[i] && std::isfinite(field.residual[i]) ? 1 : 0;
  return 2 * cores < field.observed;
}

// The epoch matched from T with the stable part's M-estimator on the points outside T's
// deformed regions (all points when T describes no majority), then refined.
RobustMatchingReport
refinedFrom(const Eigen::Matrix4d& T, const std::vector<Eigen::Vector3d>& points,
            const std::vector<int>& point_indices, const TargetSurface& reference, const ConjugateRule& rule,
            const RobustMatchingSettings& matching, const ResidualSettings& residuals,
            const RegionSettings& regions, const StableRefinementSettings& settings,
            const RobustMatchingReport& unrefined, double noise, StableRefinementReport& refinement,
            std::string& first_matching)
{
  const ResidualField field =
      computeResidualField(points, reference, rule, fitAt(unrefined.adjustment, T), noise, residuals);
  const RegionAnalysis analysis = analyseRegions(points, field, regions);
  const bool all_points = !significantMinority(field, analysis);  // T describes no majority
  std::vector<Eigen::Vector3d> kept = points;
  std::vector<int> kept_indices = point_indices;
  if (!all_points)
    selectPoints(
        points, point_indices,
        [&](std::size_t i) { return analysis.region[i] <= 0 && std::isfinite(field.residual[i]); }, kept,
        kept_indices);
  RobustMatchingReport fit =
      robustMatching(kept, kept_indices, reference, rule, stablePartMatching(matching), T);
  if (!fit.isSolutionUsable())
    return fit;
  keepHighBreakdownFigures(unrefined, fit);
  fit.held_out = 0;  // nothing of this fit was held out
  first_matching = fit.estimator + (all_points ? " on all points" : " outside its regions");
  refinement =
      refineOnStablePart(points, point_indices, reference, rule, matching, residuals, regions, settings, fit);
  return fit;
}

// a scores smaller than b by more than the standard error of a's MAD scale.
bool
clearlySmaller(const StartCandidate& a, const StartCandidate& b)
{
  if (!std::isfinite(a.scatter) || a.outside == 0)
    return false;
  if (!std::isfinite(b.scatter))
    return true;
  return a.scatter < b.scatter * (1.0 - kMadStandardError / std::sqrt(static_cast<double>(a.outside)));
}

}  // namespace

double
stablePartScatter(const std::vector<Eigen::Vector3d>& points, const TargetSurface& reference,
                  const ConjugateRule& rule, const AdjustmentReport& fit, double noise,
                  const ResidualSettings& residuals, const RegionSettings& regions,
                  std::size_t* outside_count)
{
  const ResidualField field = computeResidualField(points, reference, rule, fit, noise, residuals);
  const RegionAnalysis analysis = analyseRegions(points, field, regions);
  std::vector<double> outside;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (std::isfinite(field.residual[i]) && analysis.region[i] <= 0)
      outside.push_back(field.residual[i]);
  if (outside_count)
    *outside_count = outside.size();
  if (outside.empty() || !significantMinority(field, analysis))
    return kInf;
  return robustScale(
      Eigen::Map<const Eigen::VectorXd>(outside.data(), static_cast<Eigen::Index>(outside.size())));
}

StartChoice
chooseBetweenStarts(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& point_indices,
                    const TargetSurface& reference, const ConjugateRule& rule,
                    const RobustMatchingSettings& matching, const ResidualSettings& residuals,
                    const RegionSettings& regions, const StableRefinementSettings& settings,
                    const RobustMatchingReport& unrefined, RobustMatchingReport& robust,
                    StableRefinementReport& refinement)
{
  StartChoice choice;
  const bool lms = unrefined.method == RobustMethod::LMS;
  if (!(lms || unrefined.method == RobustMethod::MM) || !(unrefined.block_support > 0.0))
    return choice;
  const double noise = unrefined.neighbour_noise > 0.0 ? unrefined.neighbour_noise : unrefined.scale;
  if (!(noise > 0.0))  // a refused fit has no scale: nothing to test the residuals at
    return choice;
  StartCandidate kept{toString(unrefined.method), kInf, 0, robust.isSolutionUsable()};
  if (kept.usable)
    kept.scatter = stablePartScatter(points, reference, rule, robust.adjustment, noise, residuals, regions,
                                     &kept.outside);
  choice.candidates.push_back(kept);
  choice.chosen = kept.name;
  const std::pair<const char*, Eigen::Matrix4d> starts[] = {
      {lms ? "lms start" : "lts start", unrefined.high_breakdown_transformation},
      {"block start", unrefined.block_start_transformation}};
  for (const auto& start : starts) {
    StableRefinementReport r;
    std::string first_matching;
    RobustMatchingReport fit = refinedFrom(start.second, points, point_indices, reference, rule, matching,
                                           residuals, regions, settings, unrefined, noise, r, first_matching);
    // A fit whose refinement did not settle (MAX_ITERATIONS: the stable part flips between
    // rounds) is a snapshot of an oscillation, not a fit to prefer (docs/DECISIONS.md).
    StartCandidate c{start.first, kInf, 0,
                     fit.isSolutionUsable() && fit.termination == TerminationType::CONVERGED};
    if (c.usable)
      c.scatter =
          stablePartScatter(points, reference, rule, fit.adjustment, noise, residuals, regions, &c.outside);
    choice.candidates.push_back(c);
    if (c.usable && clearlySmaller(c, kept)) {
      kept = c;
      choice.chosen = c.name;
      choice.chosen_matching = first_matching;
      robust = std::move(fit);
      refinement = r;
    }
  }
  return choice;
}

}  // namespace deformation
}  // namespace pcl_ls3d
