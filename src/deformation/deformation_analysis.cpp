#include <pcl_ls3d/deformation/deformation_analysis.h>

#include <pcl_ls3d/adjustment/quality_gate.h>
#include <pcl_ls3d/estimators/neighbour_noise.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace pcl_ls3d {
namespace deformation {

namespace {

// A random sample (fixed seed) of `count` finite epoch points in input order; empty when all are
// used. Random, not every k-th point: on a gridded or scan-line cloud every k-th point lies on a
// few lines, whose neighbourhoods have no second tangent direction (the noise estimate of the
// quality gate then sees a flat, noise-free surface and the σ0 gate refuses a good fit).
std::vector<int>
matchingSample(const std::vector<Eigen::Vector3d>& epoch, std::size_t count)
{
  std::vector<int> finite;
  for (std::size_t i = 0; i < epoch.size(); ++i)
    if (epoch[i].allFinite())
      finite.push_back(static_cast<int>(i));
  if (count == 0 || finite.size() <= count)
    return {};
  std::mt19937 rng(20011);
  for (std::size_t k = 0; k < count; ++k) {  // partial Fisher–Yates
    std::uniform_int_distribution<std::size_t> pick(k, finite.size() - 1);
    std::swap(finite[k], finite[pick(rng)]);
  }
  finite.resize(count);
  std::sort(finite.begin(), finite.end());
  return finite;
}

// DeformationSettings::max_stable_scatter_ratio on the final field and its regions.
void
stableScatterGate(const std::vector<Eigen::Vector3d>& epoch, double limit, DeformationResult& out)
{
  out.field_noise = neighbourDifferenceScale(epoch, out.field.residual);
  std::vector<double> outside;
  for (std::size_t i = 0; i < out.field.residual.size(); ++i)
    if (std::isfinite(out.field.residual[i]) && out.regions.region[i] <= 0)
      outside.push_back(std::abs(out.field.residual[i]));
  if (outside.empty() || !(out.field_noise > 0.0))
    return;
  const auto mid = outside.begin() + static_cast<std::ptrdiff_t>(outside.size() / 2);
  std::nth_element(outside.begin(), mid, outside.end());
  out.stable_scatter = 1.4826 * *mid;
  const double ratio = out.stable_scatter / out.field_noise;
  if (!(limit > 0.0) || !(ratio > limit))
    return;
  char why[320];
  std::snprintf(why, sizeof why,
                "NOT TRUSTWORTHY: the stable part scatters by %.4g, %.3g x the noise of neighbouring "
                "residuals %.4g (limit %.3g): the fit is tilted between the stable and the moved part",
                out.stable_scatter, ratio, out.field_noise, limit);
  RobustMatchingReport& m = out.matching;
  m.adjustment.termination = m.termination = TerminationType::UNRELIABLE;
  m.adjustment.quality.trustworthy = false;
  m.message += (m.message.empty() ? "" : "; ") + std::string(why);
}

}  // namespace

bool
DeformationSettings::isValid(std::string* why) const
{
  if (!(max_stable_scatter_ratio >= 0.0)) {
    if (why)
      *why = "max_stable_scatter_ratio must be >= 0 (0: off)";
    return false;
  }
  return matching.isValid(why) && residuals.isValid(why) && regions.isValid(why) && refinement.isValid(why);
}

namespace {

DeformationResult
analyseWithModel(const std::vector<Eigen::Vector3d>& epoch, const TargetSurface& reference,
                 const ConjugateRule& rule, const DeformationSettings& settings, const Eigen::Matrix4d& guess)
{
  DeformationResult out;
  const std::vector<int> sample = matchingSample(epoch, settings.matching_points);
  std::vector<Eigen::Vector3d> sampled;
  if (!sample.empty()) {
    sampled.reserve(sample.size());
    for (int i : sample)
      sampled.push_back(epoch[static_cast<std::size_t>(i)]);
  }
  const std::vector<Eigen::Vector3d>& matched = sample.empty() ? epoch : sampled;
  // The refinement and the choice between starts below correct the compromise that the
  // kept-scale gate refuses (robust_matching.h): the estimator's own fit is not gated here.
  RobustMatchingSettings own = settings.matching;
  own.max_kept_scale_ratio = 0.0;
  out.matching = robustMatching(matched, sample, reference, rule, own, guess);
  // A fit the quality gate refused (at 49 % deformed it rejects the patch and the stable part's
  // noise tail: more than half) may still be rescued by the fit from another start.
  const bool other_starts = out.matching.block_support > 0.0 && out.matching.adjustment.hasEstimate() &&
                            settings.refinement.max_rounds > 0;
  if (!out.matching.isSolutionUsable() && !other_starts)
    return out;
  ResidualSettings rs = settings.residuals;
  rs.max_distance = std::min(rs.max_distance, settings.matching.adjustment.max_correspondence_distance);
  RegionSettings regions = settings.regions;
  if (regions.plane_axis < 0 && settings.rule == ConjugateRuleType::LZD)
    regions.plane_axis = 2;  // LZD residuals are heights: areas and volumes on the xy plane
  const std::string robust_estimator = out.matching.estimator;
  const RobustMatchingReport unrefined = out.matching;
  if (out.matching.isSolutionUsable())
    out.refinement = refineOnStablePart(matched, sample, reference, rule, settings.matching, rs, regions,
                                        settings.refinement, out.matching);
  if (other_starts)
    out.start_choice = chooseBetweenStarts(matched, sample, reference, rule, settings.matching, rs, regions,
                                           settings.refinement, unrefined, out.matching, out.refinement);
  if (!out.matching.isSolutionUsable())
    return out;
  std::string estimator = robust_estimator;
  const bool restarted = !out.start_choice.candidates.empty() &&
                         out.start_choice.chosen != out.start_choice.candidates.front().name;
  if (restarted && !unrefined.isSolutionUsable())
    estimator += "; its own fit refused by the quality gate";
  if (restarted)
    estimator += "; chosen: the fit from its " + out.start_choice.chosen + " (" +
                 out.start_choice.chosen_matching + ")";
  if (out.refinement.rounds > 0)
    estimator += ", then " + out.matching.estimator + " on the stable part (" +
                 std::to_string(out.refinement.left_out) + " left out)";
  out.matching.estimator = estimator;
  out.field = computeResidualField(epoch, reference, rule, out.matching.adjustment, out.matching.scale, rs);
  out.regions = analyseRegions(epoch, out.field, regions);
  stableScatterGate(epoch, settings.max_stable_scatter_ratio, out);
  return out;
}

}  // namespace

bool
rotationsUndetermined(const DeformationResult& r, const AdjustmentSettings& adjustment)
{
  const bool rotates = !adjustment.isFixed(3) || !adjustment.isFixed(4) || !adjustment.isFixed(5);
  return rotates && !r.ok() && r.matching.adjustment.hasEstimate() &&
         moveUndetermined(r.matching.adjustment.quality, adjustment);
}

AdjustmentSettings
translationAlone(const AdjustmentSettings& settings)
{
  AdjustmentSettings s = settings;
  for (int q = 3; q < 7; ++q)
    s.fixParameter(q);
  return s;
}

DeformationResult
analyseDeformation(const std::vector<Eigen::Vector3d>& epoch, const TargetSurface& reference,
                   const ConjugateRule& rule, const DeformationSettings& settings,
                   const Eigen::Matrix4d& guess)
{
  std::string why;
  if (!settings.isValid(&why)) {
    DeformationResult out;
    out.matching.termination = TerminationType::INVALID_INPUT;
    out.matching.message = "invalid settings: " + why;
    return out;
  }
  DeformationResult out = analyseWithModel(epoch, reference, rule, settings, guess);
  if (!settings.translation_when_undetermined || !rotationsUndetermined(out, settings.matching.adjustment))
    return out;
  DeformationSettings shift = settings;
  shift.matching.adjustment = translationAlone(settings.matching.adjustment);
  // The shift cannot follow the tilts the data fix only weakly: its stable part keeps their
  // trace (1.56 x sigma_d on the gentle terrain of the tests), which is the model's limit, said
  // in model_note, not the estimator's compromise the stable-scatter gate looks for.
  shift.max_stable_scatter_ratio = 0.0;
  shift.matching.sample_size = std::min(shift.matching.sample_size, 4);  // p + 1, as for 6 and 7
  DeformationResult reduced = analyseWithModel(epoch, reference, rule, shift, guess);
  if (!reduced.ok()) {
    out.matching.message += "; with the translation alone: " + reduced.matching.message;
    return out;
  }
  const QualityFigures& q = out.matching.adjustment.quality;
  char note[240];
  std::snprintf(note, sizeof note,
                "translation only: the data do not determine the %s fit (it moved %.3g, its "
                "position sigma %.3g is %.3g x the surfaces' noise)",
                settings.matching.adjustment.isFixed(6) ? "rigid" : "similarity", q.movement,
                q.position_sigma, q.position_sigma / q.expected_noise);
  reduced.model_note = note;
  return reduced;
}

}  // namespace deformation
}  // namespace pcl_ls3d
