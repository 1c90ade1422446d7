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

/// The settings deformation analysis runs the engine with.
RobustMatchingSettings
deformationSettings(const RobustMatchingSettings& settings)
{
  // Deformation analysis needs the residual of every epoch point: no automatic reach cutting
  // the moved part out of the observations.
  RobustMatchingSettings s = settings;
  s.adjustment.automatic_reach = false;
  // Rejecting the moved part is the method: up to the estimators' breakdown point, not the
  // few per cent a good least-squares fit rejects.
  s.adjustment.max_rejected_fraction = std::max(s.adjustment.max_rejected_fraction, 0.5);
  return s;
}

/// Non-finite points are no observations (as PCL drops them); indices keep the caller's.
void
finiteObservations(const std::vector<Eigen::Vector3d>& all_points, const std::vector<int>& all_indices,
                   std::vector<Eigen::Vector3d>& points, std::vector<int>& point_indices)
{
  points.reserve(all_points.size());
  point_indices.reserve(all_points.size());
  for (std::size_t i = 0; i < all_points.size(); ++i)
    if (all_points[i].allFinite()) {
      points.push_back(all_points[i]);
      point_indices.push_back(i < all_indices.size() ? all_indices[i] : static_cast<int>(i));
    }
}

/// One robust matching as Li et al. run it: the all-points least-squares start, the
/// high-breakdown start (LMS, MM) and the final IRLS adjustment; each stage returns false when
/// the report is final.
class RobustMatchingRun
{
public:
  RobustMatchingRun(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& point_indices,
                    const TargetSurface& reference, const ConjugateRule& rule,
                    const RobustMatchingSettings& s, const Eigen::Matrix4d& guess,
                    RobustMatchingReport& report)
      : points_(points), point_indices_(point_indices), reference_(reference), rule_(rule), s_(s),
        report_(report), from_(guess)
  {}

  bool
  leastSquaresStart();
  bool
  highBreakdownStart();
  void
  finalAdjustment();

private:
  bool
  highBreakdown() const
  {
    return s_.method == RobustMethod::LMS || s_.method == RobustMethod::MM;
  }
  /// A failure of the robust stages, which say where they began.
  bool
  failed(TerminationType type, const std::string& message)
  {
    fail(report_, type, start_note_.empty() ? message : start_note_ + "; from the guess: " + message);
    return false;
  }
  RobustEstimator::Ptr
  finalWeightFunction();
  void
  reportFinal(const RobustEstimator& w);

  const std::vector<Eigen::Vector3d>& points_;
  const std::vector<int>& point_indices_;
  const TargetSurface& reference_;
  const ConjugateRule& rule_;
  const RobustMatchingSettings& s_;
  RobustMatchingReport& report_;
  SurfaceMatchingCore core_;  // one engine for both adjustments, as its buffers carry over
  Eigen::Matrix4d from_;      // where the next stage begins
  std::string start_note_;    // why the robust stages begin at the guess
  double fixed_scale_ = 0.0;
  std::vector<std::uint8_t> held_out_;  // MM: points beyond 2.5 ŝ of the start
};

/// 1. All-points least squares (Li: LHD with all matchable points).
bool
RobustMatchingRun::leastSquaresStart()
{
  if (!s_.least_squares_start && s_.method != RobustMethod::LEAST_SQUARES)
    return true;
  const LeastSquaresEstimator ls;
  report_.start = core_.run(points_, point_indices_, reference_, rule_, ls, s_.adjustment, from_);
  report_.iterations = report_.start.iterations;
  // The start only brings the surfaces close: with much of the surface moved the quality gate
  // rightly calls it untrustworthy, but its estimate is what the robust stages start from,
  // unless it slid off the overlap. Plain least squares has no other answer; an input the
  // start found nothing in, or a start that failed at the guess itself, is no better there.
  start_note_ = startSlidOff(report_.start, s_.adjustment);
  const bool nothing_to_retry = report_.start.termination == TerminationType::INVALID_INPUT ||
                                report_.start.termination == TerminationType::NO_OVERLAP ||
                                report_.start.iterations == 0;  // it failed at the guess itself
  if (!report_.start.hasEstimate() && (s_.method == RobustMethod::LEAST_SQUARES || nothing_to_retry)) {
    report_.adjustment = report_.start;
    fail(report_, report_.start.termination, "least-squares start: " + report_.start.message);
    return false;
  }
  if (start_note_.empty())
    from_ = report_.start.transformation;
  return true;
}

/// 2. High-breakdown start (LMS, MM): the fixed scale of the M-step and, for MM, the points
/// held out of it.
bool
RobustMatchingRun::highBreakdownStart()
{
  if (!highBreakdown())
    return true;
  LinearizedMatching lin;
  TerminationType failure = TerminationType::NO_OVERLAP;
  std::string why;
  if (!lin.reset(points_, reference_, rule_, s_.adjustment, from_, &why, &failure))
    return failed(failure, why);
  const std::size_t matched = lin.size();
  if (matched < static_cast<std::size_t>(std::max(s_.sample_size, lin.freeParameters() + 1)))
    return failed(TerminationType::TOO_FEW_OBSERVATIONS,
                  "only " + std::to_string(matched) + " epoch points have a conjugate point (sample size " +
                      std::to_string(s_.sample_size) + ")");
  if (!highBreakdownSearch(lin, s_, report_))
    return failed(TerminationType::SINGULAR,
                  "no subset of " + std::to_string(s_.sample_size) + " points determined the parameters");
  from_ = report_.high_breakdown_transformation;
  if (!(s_.method == RobustMethod::LMS && s_.lms_scale == LmsScale::MAD))
    fixed_scale_ = report_.high_breakdown_scale;
  if (s_.method == RobustMethod::MM && s_.mm_hold_out_beyond_start)
    held_out_ = beyondStart(lin, lin.parametersOf(from_), fixed_scale_, report_.held_out);
  return true;
}

/// The method's weight function (none for LS), masked where MM holds points out.
RobustEstimator::Ptr
RobustMatchingRun::finalWeightFunction()
{
  RobustEstimator::Ptr w = weightFunction(s_.method, s_.constant, fixed_scale_);
  if (!held_out_.empty())
    w = std::make_shared<MaskedEstimator>(w, std::move(held_out_));
  return w;
}

/// 3. The final adjustment: IRLS with the method's weight function (none for LS).
void
RobustMatchingRun::finalAdjustment()
{
  const RobustEstimator::Ptr w = finalWeightFunction();
  if (s_.method == RobustMethod::LEAST_SQUARES)
    report_.adjustment = report_.start;
  else {
    report_.adjustment = core_.run(points_, point_indices_, reference_, rule_, *w, s_.adjustment, from_);
    report_.iterations += report_.adjustment.iterations;
  }
  reportFinal(*w);
  if (highBreakdown())
    keptScaleGate(points_, point_indices_, s_.max_kept_scale_ratio, report_);
}

/// The report's estimator, outcome and scale from the final adjustment.
void
RobustMatchingRun::reportFinal(const RobustEstimator& w)
{
  report_.estimator = highBreakdown() ? std::string(toString(s_.method)) + "(" +
                                            std::to_string(report_.subsets_drawn) + " subsets) + " + w.name()
                                      : w.name();
  report_.termination = report_.adjustment.termination;
  report_.message = report_.adjustment.message;
  if (!start_note_.empty() && s_.method != RobustMethod::LEAST_SQUARES)
    report_.message +=
        (report_.message.empty() ? "" : "; ") + start_note_ + ": the robust stages began at the guess";
  if (report_.adjustment.isSolutionUsable())
    report_.scale = finalScale(w, report_.adjustment);
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
  const RobustMatchingSettings s = deformationSettings(settings);
  std::vector<Eigen::Vector3d> points;
  std::vector<int> point_indices;
  finiteObservations(all_points, all_indices, points, point_indices);
  RobustMatchingReport report;
  report.method = s.method;
  report.estimator = toString(s.method);
  std::string why;
  if (!s.isValid(&why))
    return fail(report, TerminationType::INVALID_INPUT, "invalid settings: " + why);
  RobustMatchingRun run(points, point_indices, reference, rule, s, guess, report);
  if (run.leastSquaresStart() && run.highBreakdownStart())
    run.finalAdjustment();
  return report;
}

}  // namespace pcl_ls3d
