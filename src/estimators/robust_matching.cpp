#include <pcl_ls3d/estimators/robust_matching.h>

#include <pcl_ls3d/adjustment/surface_matching_core.h>
#include <pcl_ls3d/estimators/masked_estimator.h>
#include <pcl_ls3d/estimators/neighbour_noise.h>
#include <pcl_ls3d/sample_consensus/block_trimmed_squares.h>
#include <pcl_ls3d/sample_consensus/linearized_matching.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <unordered_map>

namespace pcl_ls3d {

namespace {

const char* const kNames[] = {"ls", "zuo", "huber", "m", "md", "lms", "mm"};

RobustMatchingReport&
fail(RobustMatchingReport& report, TerminationType type, const std::string& message)
{
  report.termination = type;
  report.message = message;
  return report;
}

/// The weight function of a method (LMS: Li's M-step, MM: the Tukey M-step at a fixed scale).
RobustEstimator::Ptr
weightFunction(RobustMethod method, double constant, double fixed_scale)
{
  const bool given = std::isfinite(constant);
  switch (method) {
  case RobustMethod::LEAST_SQUARES:
    return std::make_shared<LeastSquaresEstimator>();
  case RobustMethod::ZUO:
    return std::make_shared<ZuoEstimator>(given ? constant : 6.0);
  case RobustMethod::HUBER:
    return std::make_shared<HuberEstimator>(given ? constant : kHuber95);
  case RobustMethod::M:
    return std::make_shared<TukeyEstimator>(given ? constant : kTukey95);
  case RobustMethod::LMS:
    if (!(fixed_scale > 0.0))  // LmsScale::MAD: eq. 7 on all residuals, every iteration
      return std::make_shared<TukeyEstimator>(given ? constant : kTukey95);
    return std::make_shared<TukeyEstimator>(given ? constant : kTukey95, ScaleRule::FIXED, fixed_scale);
  case RobustMethod::MD:
    return std::make_shared<MdEstimator>(given ? constant : kTukey95);
  case RobustMethod::MM:
    return std::make_shared<TukeyEstimator>(given ? constant : kTukey95, ScaleRule::FIXED, fixed_scale);
  }
  return nullptr;
}

/// σ̂ of the estimator on the final residuals.
double
finalScale(const RobustEstimator& estimator, const AdjustmentReport& r)
{
  const Eigen::VectorXd v =
      Eigen::Map<const Eigen::VectorXd>(r.residuals.data(), static_cast<Eigen::Index>(r.residuals.size()));
  const Eigen::VectorXd none;
  return estimator.scale(WeightingInput(v, none, none, r.sigma0));
}

/// Largest displacement between two estimates over the corners of the points' box.
double
maxDisplacement(const LinearizedMatching& lin, const Vector7d& a, const Vector7d& b)
{
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : lin.reducedPoints())
    if (p.allFinite())
      box.extend(p);
  const Eigen::Matrix4d Ta = SimilarityTransform(a).matrix(), Tb = SimilarityTransform(b).matrix();
  double d = 0.0;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector4d x = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)).homogeneous();
    d = std::max(d, (Ta * x - Tb * x).head<3>().norm());
  }
  return d;
}

/// The scale the M-step keeps fixed, from the high-breakdown fit X (its residuals v over all
/// matched observations): LMS s0 (recomputed at X, which may be an earlier round's) and σ*;
/// MM the LTS scale reweighted, or the S-scale; at most the neighbour noise when capped.
double
fixedScale(const LinearizedMatching& lin, const Vector7d& X, const RobustMatchingSettings& s,
           double search_scale, double& neighbour_noise)
{
  Eigen::VectorXd v;
  lin.residuals(X, v);
  double fixed = 0.0;
  if (s.method == RobustMethod::LMS) {
    const double s0 = lmsScale(lmsCriterion(lin, X), lin.size(), lin.freeParameters());
    fixed = s.lms_scale == LmsScale::PRELIMINARY ? s0 : lmsFinalScale(v, s0, lin.freeParameters());
    fixed = fixed > 0.0 ? fixed : s0;
  } else {
    fixed = s.mm_scale == MmScale::S_SCALE ? mScale(v, kTukeyS50, 0.5, search_scale)
                                           : reweightedScale(v, search_scale);
    fixed = fixed > 0.0 ? fixed : search_scale;
  }
  neighbour_noise = neighbourDifferenceScale(lin.reducedPoints(), lin.pointResiduals(v));
  if (s.cap_scale_by_neighbour_noise && neighbour_noise > 0.0)
    fixed = std::min(fixed, neighbour_noise);
  return fixed;
}

/// Points whose first observation lies beyond kReweightingCut ŝ of the high-breakdown fit X;
/// 1 = beyond.
std::vector<std::uint8_t>
beyondStart(const LinearizedMatching& lin, const Vector7d& X, double scale, std::size_t& count)
{
  Eigen::VectorXd v;
  lin.residuals(X, v);
  const std::vector<double> first = lin.pointResiduals(v);
  std::vector<std::uint8_t> out(first.size(), 0);
  count = 0;
  for (std::size_t i = 0; i < first.size(); ++i)
    if (std::abs(first[i]) > kReweightingCut * scale) {  // false for NaN: no observation
      out[i] = 1;
      ++count;
    }
  return out;
}

/// The high-breakdown stage: rounds of subset searches, re-linearised at the last estimate
/// while it moves by more than a tenth of the search's scale.
bool
highBreakdownSearch(LinearizedMatching& lin, const RobustMatchingSettings& s, RobustMatchingReport& report)
{
  const bool lms = s.method == RobustMethod::LMS;
  SubsetSearchSettings ss;
  ss.subsets = s.subsetCount();
  ss.sample_size = s.sample_size;
  ss.score_points = s.score_points;
  Vector7d X = lin.linearizationPoint();
  bool have = false;
  for (int round = 1; round <= s.max_rounds; ++round) {
    ss.seed = s.seed + static_cast<std::uint32_t>(round - 1);
    SubsetSearchResult res = lms ? leastMedianOfSquares(lin, ss) : leastTrimmedSquares(lin, ss);
    report.rounds = round;
    report.subsets_drawn += res.drawn;
    if (!res.ok) {
      if (!have)
        return false;
      break;
    }
    if (have) {  // the previous round's estimate competes on the new linearisation
      const double previous = lms ? lmsCriterion(lin, X) : ltsCriterion(lin, X, ss.coverage);
      if (previous <= res.criterion) {
        res.parameters = X;
        res.criterion = previous;
      }
    }
    const double moved = maxDisplacement(lin, res.parameters, lin.linearizationPoint());
    X = res.parameters;
    report.search = res;
    have = true;
    if (!(moved > 0.1 * res.scale) || round == s.max_rounds || !lin.relinearize(X))
      break;
  }
  report.high_breakdown_transformation = lin.matrixOf(X);
  report.high_breakdown_scale = fixedScale(lin, X, s, report.search.scale, report.neighbour_noise);
  if (s.block_start) {
    BlockTrimmedSquaresSettings bs;
    bs.seed = s.seed;
    const BlockTrimmedSquaresResult blocks = blockTrimmedSquares(lin, X, bs);
    if (blocks.ok) {
      report.block_start_transformation = lin.matrixOf(blocks.parameters);
      report.block_support = blocks.support;
    }
  }
  return true;
}

/// Why the least-squares start is no place for the robust stages to begin ("" when it is).
/// On nearly flat terrain with a raised patch the all-points fit slides sideways off the
/// overlap (to 0 observations, or below the quality gate's share of its first ones); the
/// robust stages then begin at the guess, which the start could not improve.
std::string
startSlidOff(const AdjustmentReport& start, const AdjustmentSettings& settings)
{
  if (!start.hasEstimate())
    return std::string("the least-squares start ended ") + terminationTypeToString(start.termination) + " (" +
           start.message + ")";
  if (start.quality.observations_kept < settings.min_observations_kept) {
    char kept[32];
    std::snprintf(kept, sizeof kept, "%.3f", start.quality.observations_kept);
    return std::string("the least-squares start slid off the overlap (kept ") + kept +
           " of its first correspondences)";
  }
  return {};
}

// The final fit's residuals: per observed point (its first observation) its position and
// residual, and |v| of every observation the estimator kept (weight > 0).
void
finalResiduals(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& point_indices,
               const AdjustmentReport& fit, std::vector<Eigen::Vector3d>& positions,
               std::vector<double>& residuals, std::vector<double>& kept)
{
  std::unordered_map<int, std::size_t> position_of;
  for (std::size_t k = 0; k < points.size(); ++k)
    position_of.emplace(point_indices[k], k);
  const std::size_t m =
      std::min({fit.residuals.size(), fit.weights.size(), fit.observation_source_index.size()});
  int last = std::numeric_limits<int>::min();
  for (std::size_t j = 0; j < m; ++j) {
    if (fit.weights[j] > 0.0)
      kept.push_back(std::abs(fit.residuals[j]));
    const int index = fit.observation_source_index[j];
    const auto at = position_of.find(index);
    if (index == last || at == position_of.end())
      continue;
    last = index;
    positions.push_back(points[at->second]);
    residuals.push_back(fit.residuals[j]);
  }
}

// RobustMatchingSettings::max_kept_scale_ratio on a usable LMS / MM fit.
void
keptScaleGate(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& point_indices, double limit,
              RobustMatchingReport& report)
{
  std::vector<Eigen::Vector3d> positions;
  std::vector<double> residuals, kept;
  finalResiduals(points, point_indices, report.adjustment, positions, residuals, kept);
  report.final_neighbour_noise = neighbourDifferenceScale(positions, residuals);
  if (kept.empty() || !(report.final_neighbour_noise > 0.0))
    return;
  const auto mid = kept.begin() + static_cast<std::ptrdiff_t>(kept.size() / 2);
  std::nth_element(kept.begin(), mid, kept.end());
  report.kept_scale = 1.4826 * *mid;
  const double ratio = report.kept_scale / report.final_neighbour_noise;
  if (!(limit > 0.0) || !(ratio > limit) || !report.adjustment.isSolutionUsable())
    return;
  char why[320];
  std::snprintf(why, sizeof why,
                "NOT TRUSTWORTHY: the residuals the M-step kept have a scale of %.4g, %.3g x the "
                "noise of neighbouring residuals %.4g (limit %.3g): the fit compromises between the "
                "stable and the moved part",
                report.kept_scale, ratio, report.final_neighbour_noise, limit);
  report.adjustment.termination = TerminationType::UNRELIABLE;
  report.adjustment.quality.trustworthy = false;
  report.adjustment.message += (report.adjustment.message.empty() ? "" : "; ") + std::string(why);
  report.termination = TerminationType::UNRELIABLE;
  report.message += (report.message.empty() ? "" : "; ") + std::string(why);
}

}  // namespace

const char*
toString(RobustMethod method)
{
  return kNames[static_cast<int>(method)];
}

bool
parseRobustMethod(const std::string& text, RobustMethod& method)
{
  std::string t = text;
  std::transform(t.begin(), t.end(), t.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (t == "least-squares")
    t = "ls";
  else if (t == "m-d" || t == "gm")
    t = "md";
  else if (t == "tukey")
    t = "m";
  for (int i = 0; i < 7; ++i)
    if (t == kNames[i]) {
      method = static_cast<RobustMethod>(i);
      return true;
    }
  return false;
}

bool
RobustMatchingSettings::isValid(std::string* why) const
{
  auto bad = [why](const char* reason) {
    if (why)
      *why = reason;
    return false;
  };
  std::string adj;
  if (!adjustment.isValid(&adj)) {
    if (why)
      *why = adj;
    return false;
  }
  if (std::isfinite(constant) && !(constant > 0.0))
    return bad("the tuning constant must be > 0");
  if (subsets < 0 || subsets > 10000000)
    return bad("subsets must be in [0, 1e7] (0: from eq. 12)");
  if (!(contamination > 0.0 && contamination < 1.0))
    return bad("contamination must be in (0, 1)");
  if (sample_size < 1 || sample_size > 64)
    return bad("sample_size must be in [1, 64]");
  if (max_rounds < 1)
    return bad("max_rounds must be >= 1");
  if (!(max_kept_scale_ratio >= 0.0))
    return bad("max_kept_scale_ratio must be >= 0 (0: off)");
  return true;
}

std::string
RobustMatchingReport::brief() const
{
  // The estimator's name grows with the stages run (deformation: the refinement too): no fixed
  // buffer around it.
  char tail[128];
  std::snprintf(tail, sizeof(tail), ": %s, sigma_hat %.4g, %d iterations",
                terminationTypeToString(termination), scale, iterations);
  std::string line = estimator + tail;
  if (subsets_drawn > 0)
    line += ", " + std::to_string(subsets_drawn) + " subsets in " + std::to_string(rounds) + " round(s)";
  return line;
}

RobustMatchingReport
robustMatching(const std::vector<Eigen::Vector3d>& all_points, const std::vector<int>& all_indices,
               const TargetSurface& reference, const ConjugateRule& rule,
               const RobustMatchingSettings& settings, const Eigen::Matrix4d& guess)
{
  // Deformation analysis needs the residual of every epoch point: no automatic reach cutting
  // the moved part out of the observations.
  RobustMatchingSettings s = settings;
  s.adjustment.automatic_reach = false;
  // Rejecting the moved part is the method: up to the estimators' breakdown point, not the
  // few per cent a good least-squares fit rejects.
  s.adjustment.max_rejected_fraction = std::max(s.adjustment.max_rejected_fraction, 0.5);
  // Non-finite points are no observations (as PCL drops them); indices keep the caller's.
  std::vector<Eigen::Vector3d> points;
  std::vector<int> point_indices;
  points.reserve(all_points.size());
  point_indices.reserve(all_points.size());
  for (std::size_t i = 0; i < all_points.size(); ++i)
    if (all_points[i].allFinite()) {
      points.push_back(all_points[i]);
      point_indices.push_back(i < all_indices.size() ? all_indices[i] : static_cast<int>(i));
    }
  RobustMatchingReport report;
  report.method = s.method;
  report.estimator = toString(s.method);
  std::string why;
  if (!s.isValid(&why))
    return fail(report, TerminationType::INVALID_INPUT, "invalid settings: " + why);

  // 1. All-points least squares (Li: LHD with all matchable points).
  SurfaceMatchingCore core;
  const LeastSquaresEstimator ls;
  Eigen::Matrix4d from = guess;
  std::string start_note;  // why the robust stages begin at the guess
  if (s.least_squares_start || s.method == RobustMethod::LEAST_SQUARES) {
    report.start = core.run(points, point_indices, reference, rule, ls, s.adjustment, guess);
    report.iterations = report.start.iterations;
    // The start only brings the surfaces close: with much of the surface moved the quality gate
    // rightly calls it untrustworthy, but its estimate is what the robust stages start from,
    // unless it slid off the overlap. Plain least squares has no other answer; an input the
    // start found nothing in, or a start that failed at the guess itself, is no better there.
    start_note = startSlidOff(report.start, s.adjustment);
    const bool nothing_to_retry = report.start.termination == TerminationType::INVALID_INPUT ||
                                  report.start.termination == TerminationType::NO_OVERLAP ||
                                  report.start.iterations == 0;  // it failed at the guess itself
    if (!report.start.hasEstimate() && (s.method == RobustMethod::LEAST_SQUARES || nothing_to_retry)) {
      report.adjustment = report.start;
      return fail(report, report.start.termination, "least-squares start: " + report.start.message);
    }
    if (start_note.empty())
      from = report.start.transformation;
  }
  double fixed_scale = 0.0;
  std::vector<std::uint8_t> held_out;  // MM: points beyond 2.5 ŝ of the start
  const auto failed = [&](TerminationType type, const std::string& message) {
    return fail(report, type, start_note.empty() ? message : start_note + "; from the guess: " + message);
  };

  // 2. High-breakdown start (LMS, MM).
  if (s.method == RobustMethod::LMS || s.method == RobustMethod::MM) {
    LinearizedMatching lin;
    TerminationType failure = TerminationType::NO_OVERLAP;
    if (!lin.reset(points, reference, rule, s.adjustment, from, &why, &failure))
      return failed(failure, why);
    const std::size_t matched = lin.size();
    if (matched < static_cast<std::size_t>(std::max(s.sample_size, lin.freeParameters() + 1)))
      return failed(TerminationType::TOO_FEW_OBSERVATIONS,
                    "only " + std::to_string(matched) + " epoch points have a conjugate point (sample size " +
                        std::to_string(s.sample_size) + ")");
    if (!highBreakdownSearch(lin, s, report))
      return failed(TerminationType::SINGULAR,
                    "no subset of " + std::to_string(s.sample_size) + " points determined the parameters");
    from = report.high_breakdown_transformation;
    if (!(s.method == RobustMethod::LMS && s.lms_scale == LmsScale::MAD))
      fixed_scale = report.high_breakdown_scale;
    if (s.method == RobustMethod::MM && s.mm_hold_out_beyond_start)
      held_out = beyondStart(lin, lin.parametersOf(from), fixed_scale, report.held_out);
  }

  // 3. The final adjustment: IRLS with the method's weight function (none for LS).
  RobustEstimator::Ptr w = weightFunction(s.method, s.constant, fixed_scale);
  if (!held_out.empty())
    w = std::make_shared<MaskedEstimator>(w, std::move(held_out));
  if (s.method == RobustMethod::LEAST_SQUARES)
    report.adjustment = report.start;
  else {
    report.adjustment = core.run(points, point_indices, reference, rule, *w, s.adjustment, from);
    report.iterations += report.adjustment.iterations;
  }
  report.estimator = s.method == RobustMethod::LMS || s.method == RobustMethod::MM
                         ? std::string(toString(s.method)) + "(" + std::to_string(report.subsets_drawn) +
                               " subsets) + " + w->name()
                         : w->name();
  report.termination = report.adjustment.termination;
  report.message = report.adjustment.message;
  if (!start_note.empty() && s.method != RobustMethod::LEAST_SQUARES)
    report.message +=
        (report.message.empty() ? "" : "; ") + start_note + ": the robust stages began at the guess";
  if (report.adjustment.isSolutionUsable())
    report.scale = finalScale(*w, report.adjustment);
  if (s.method == RobustMethod::LMS || s.method == RobustMethod::MM)
    keptScaleGate(points, point_indices, s.max_kept_scale_ratio, report);
  return report;
}

}  // namespace pcl_ls3d
