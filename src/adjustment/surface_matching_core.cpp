#include <pcl_ls3d/adjustment/gauss_markov.h>
#include <pcl_ls3d/adjustment/iteration_control.h>
#include <pcl_ls3d/adjustment/noise_floor.h>
#include <pcl_ls3d/adjustment/quality_gate.h>
#include <pcl_ls3d/adjustment/similarity_jacobian.h>
#include <pcl_ls3d/adjustment/surface_matching_core.h>
#include <pcl_ls3d/adjustment/surface_noise.h>

#include "matching_steps.h"
#include "rules/target_overlap.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace pcl_ls3d {

namespace {

using namespace detail;

AdjustmentReport&
fail(AdjustmentReport& report, TerminationType type, const std::string& message)
{
  report.termination = type;
  report.message = message;
  return report;
}

// Empty input, invalid settings or guess: the reason, or an empty string.
std::string
invalidInput(const std::vector<Eigen::Vector3d>& source, const TargetSurface& target,
             const AdjustmentSettings& settings, const Eigen::Matrix4d& guess)
{
  std::string why;
  if (!settings.isValid(&why))
    return "invalid settings: " + why;
  if (source.empty())
    return "no valid (finite) source points";
  if (target.size() < 3)
    return "fewer than 3 valid target points";
  if (!guess.allFinite())
    return "initial guess is not finite";
  return "";
}

// The state of one pair adjustment between the stages.
struct PairRun
{
  PairSetup setup;                        // stage 1: the source block (estimated) and the target's
  GaussMarkovProblem problem;             // a-priori observations and the rank-test scaling
  ScaleColumnCorrection eiv;              // errors in variables of the scale column
  GaussMarkovSolution sol;                // the last solve
  Vector7d start;                         // the parameters at the initial guess
  double source_noise = 0.0;              // σ_s, the source's own roughness
  double start_scale = 0.0;               // 1.4826 · median |l| at the initial guess
  std::size_t start_correspondences = 0;  // observations at the initial guess
  double spacing = 0.0;                   // the target's point spacing (nearest-neighbour median)
  double guess_uncertainty = 0.0;         // the annealed cut's floor in the first iteration
  double normal_variance = -1.0;          // σ_u² of the target's normals where observed (< 0: not yet)
  bool reset = false;                     // this iteration moved a newly held parameter back to its start

  void
  prepare(const AdjustmentSettings& settings, const std::vector<Eigen::Vector3d>& reduced)
  {
    problem.apriori_values = setup.source.apriori_values;
    problem.apriori_weights = setup.source.apriori_weights;
    problem.determinability_threshold = settings.determinability_threshold;
    problem.scaling = rankTestScaling(setup.radius);
    start = setup.source.values;
    source_noise = sourceNoise(reduced, setup);
    guess_uncertainty = settings.guess_uncertainty > 0.0 ? settings.guess_uncertainty
                                                         : std::min(0.01 * setup.source_box.diagonal().norm(),
                                                                    settings.max_correspondence_distance);
    if (settings.correct_source_noise)
      eiv.setSourceNoise(source_noise);
    sol.qxx = Matrix7d::Zero();
  }
};

// The floor of the estimator's cut in iteration `it` (AdjustmentSettings::guess_uncertainty):
// the guess's possible error at first, halved each iteration, until the estimator's own cut
// (K σ0) is the larger.
double
annealedCut(double guess_uncertainty, int it)
{
  return std::ldexp(guess_uncertainty, 1 - it);
}

// No conjugate point at the start although source points lie over the target's extent: a
// target with no surface there (its points collinear or coincident) is not a lack of overlap.
AdjustmentReport&
noConjugatePoint(const std::vector<Eigen::Vector3d>& source, const Eigen::Matrix4d& guess,
                 const TargetSurface& target, const PairSetup& setup, AdjustmentReport& report)
{
  const std::string degenerate =
      degenerateTargetReason(source, setup.inside, guess, target, "target", "source");
  if (!degenerate.empty())
    return fail(report, TerminationType::TOO_FEW_OBSERVATIONS, degenerate);
  return fail(report, TerminationType::NO_OVERLAP,
              "the rule found no conjugate point on the target (no overlap)");
}

// Too few conjugate points to go on (sets the report's failure).
bool
tooFewObservations(std::size_t m, int it, const AdjustmentSettings& settings, AdjustmentReport& report)
{
  if (m >= static_cast<std::size_t>(settings.min_observations))
    return false;
  report.iterations = it - 1;
  fail(report, TerminationType::TOO_FEW_OBSERVATIONS,
       "only " + std::to_string(m) + " observations (minimum " + std::to_string(settings.min_observations) +
           ")");
  return true;
}

// Parameters whose information is no more than the normals' noise (noise_floor.h): held at
// their start values in this iteration's solve. Only for rules that observe along the surface
// normal alone: ICP's tangents and point-to-point's axes fix every direction by the
// correspondences themselves.
std::vector<bool>
noiseDominatedParameters(PairRun& run, const TargetSurface& target, const SourceRows& row,
                         const Eigen::VectorXd& weights, const NormalEquations& ne)
{
  const bool normals_only =
      std::none_of(row.set.begin(), row.set.end(), [](const Observation& o) { return o.component != 0; });
  if (!normals_only)
    return std::vector<bool>(7, false);
  if (run.normal_variance < 0.0)  // a property of the target: measured once
    run.normal_variance = fittedNormalVariance(target, row.set);
  const Matrix7d M =
      noiseFloor(row.set, weights, run.normal_variance, [&row](const Observation& o) { return row.of(o); });
  return noiseDominated(ne.N, M, run.problem.apriori_weights, run.problem.scaling, kPairNoiseShare);
}

// Would the held-out scale, freed, be determinable? The noise-floor test of the solve with the
// scale free: a scale with no more information than the normals' noise would be held by
// -params 7 too, and testing it would read the misfit of held directions as a scale.
bool
freedScaleDeterminable(const PairRun& run, const SourceRows& row, const Eigen::VectorXd& weights)
{
  if (run.normal_variance < 0.0)  // a rule whose correspondences fix every direction
    return true;
  const NormalEquations ne = accumulateNormalEquations(row, weights);
  const Matrix7d M =
      noiseFloor(row.set, weights, run.normal_variance, [&row](const Observation& o) { return row.of(o); });
  Vector7d freed = run.problem.apriori_weights;
  freed[SCALE] = 0.0;
  return !noiseDominated(ne.N, M, freed, run.problem.scaling, kPairNoiseShare)[SCALE];
}

// Stage 4: solve eqs. 9–11 and apply dx; false (the report says why) when it cannot.
bool
solveAndUpdate(PairRun& run, const NormalEquations& ne, const std::vector<bool>& held, int it,
               const AdjustmentSettings& settings, AdjustmentReport& report)
{
  if (ne.n < static_cast<std::size_t>(settings.min_observations)) {
    report.iterations = it - 1;
    fail(report, TerminationType::TOO_FEW_OBSERVATIONS,
         "only " + std::to_string(ne.n) + " observations kept after robust weighting");
    return false;
  }
  ParameterBlock& block = run.setup.source;
  run.reset = false;  // a held parameter moved back to its start: the observations are stale
  for (int q = 0; q < 7; ++q)
    if (held[static_cast<std::size_t>(q)] && block.values[q] != run.start[q]) {
      block.values[q] = run.start[q];
      run.reset = true;
    }
  run.problem.current = block.values;
  GaussMarkovProblem problem = run.problem;
  holdAtStart(held, run.start, problem);
  run.sol = solveGaussMarkov(ne, problem);
  report.iterations = it;
  if (!run.sol.ok) {
    fail(report, TerminationType::SINGULAR, run.sol.message);
    return false;
  }
  reportHeldUndeterminable(held, run.sol);
  if (run.sol.redundancy <= 0) {
    fail(report, TerminationType::TOO_FEW_OBSERVATIONS, "no redundancy (r = n - u <= 0)");
    return false;
  }
  block.values += run.sol.dx;
  if (!block.values.allFinite() || !(block.values[SCALE] > 0.0)) {
    fail(report, TerminationType::DIVERGED, "the estimate became non-finite or m <= 0");
    return false;
  }
  return true;
}

// The quality gate on a finished adjustment (quality_gate.h).
void
assess(const PairRun& run, const ObservationSet& obs, const Eigen::VectorXd& weights,
       const TargetSurface& target, const AdjustmentSettings& settings, const OmittedParameterTest& held_out,
       AdjustmentReport& report)
{
  QualityInputs in;
  in.sigma0 = run.sol.sigma0;
  in.normal_sigma = normalComponentSigma(obs, weights);
  in.source_noise = run.source_noise;
  in.target_noise = estimateSurfaceNoise(target, conjugatePoints(obs));
  in.spacing = run.spacing;
  in.candidates = run.setup.inside.size();
  in.correspondences = obs.size();
  in.used = report.observations_used;
  in.start_scale = run.start_scale;
  in.start_correspondences = run.start_correspondences;
  in.start = run.start;
  in.estimate = run.setup.source.values;
  in.source_box = run.setup.source_box;
  in.covariance = report.covariance;
  report.quality = measureQuality(in, obs);
  if (held_out.ok) {
    QualityFigures& q = report.quality;
    q.held_out_scale_tested = true;
    q.held_out_scale = held_out.parameters[0].estimate;
    q.held_out_scale_sigma = held_out.parameters[0].sigma;
    q.held_out_scale_z = held_out.parameters[0].z;
    q.held_out_scale_effect = std::abs(q.held_out_scale) * run.setup.radius;
  }
  if (report.termination != TerminationType::CONVERGED &&
      report.termination != TerminationType::MAX_ITERATIONS)
    return;
  const bool scale_estimated = run.sol.determinable[SCALE];
  report.termination =
      applyQualityGate(report.quality, in, scale_estimated, settings, report.termination, report.message);
}

// Estimate, precision (eq. 14 / spatial sandwich) and reliability of the last iteration.
void
finish(const PairRun& run, const SourceRows& row, const Eigen::VectorXd& weights,
       const AdjustmentSettings& settings, const TargetSurface& target,
       const std::vector<int>& source_indices, AdjustmentReport& report)
{
  const std::size_t target_size = target.size();
  const GaussMarkovSolution& sol = run.sol;
  report.parameters = run.setup.source.values;
  report.transformation = run.setup.source.matrix();
  report.sigma0 = sol.sigma0;
  report.qxx = sol.qxx;
  report.fixed = flags7(sol.fixed);
  report.determinable = flags7(sol.determinable);
  report.redundancy = sol.redundancy;
  report.source_noise = run.eiv.active() ? run.eiv.sourceNoise() : 0.0;
  // Cell 0: the formal covariance of eq. 14 (the caller switched the sandwich off).
  const double cell = settings.spatial_precision ? precisionCell(settings, run.setup, target_size) : 0.0;
  fillCovariance(report, sol, row, weights, settings.apriori_weights, cell);
  const std::string undetermined = fillPrecision(report, sol);
  if (!undetermined.empty())
    report.message = "undeterminable from this geometry (held at their initial values): " + undetermined;
  if (report.termination == TerminationType::MAX_ITERATIONS)
    report.message += std::string(report.message.empty() ? "" : "; ") +
                      "iteration limit reached before the changes fell below the epsilons";
  if (settings.store_observations)
    storeObservations(report, sol, row, weights, source_indices);
  const OmittedParameterTest held_out =
      std::isinf(settings.held_out_z) || !freedScaleDeterminable(run, row, weights)
          ? OmittedParameterTest()
          : heldOutScaleTest(sol, row, weights, run.problem, cell);
  assess(run, row.set, weights, target, settings, held_out, report);
}

// Stage 1 after the blocks are set up: the report's frames and the run's a-priori figures.
void
prepareRun(PairRun& pair, const TargetSurface& target, const AdjustmentSettings& settings,
           const std::vector<Eigen::Vector3d>& reduced, AdjustmentReport& report)
{
  report.local_origin_source = pair.setup.source.input_origin;
  report.local_origin_target = pair.setup.source.output_origin;
  pair.prepare(settings, reduced);
  pair.spacing = estimatePointSpacing(target);
}

// One pair adjustment's inputs, engine parts and state, shared by the iteration's stages.
struct PairLoop
{
  const std::vector<Eigen::Vector3d>& source;
  const TargetSurface& target;
  const RobustEstimator& estimator;
  const AdjustmentSettings& settings;
  const Eigen::Matrix4d& guess;
  const IterationHooks& hooks;
  PairMatcher& matcher;
  ObservationWeighting& weighting;
  const BlockLinearization& target_pose;
  IterationControl& control;
  PairRun& pair;
  AdjustmentReport& report;
};

// How an iteration ended.
enum class Step
{
  NEXT,       // go on iterating
  CONVERGED,  // the estimate settled, or a hook stopped the loop
  FAILED      // the report says why
};

// Stage 2: conjugate points of the sampled source points under the current pose (§2.2), less
// those the observation filter drops; nullptr (the report says why) when the filter left none.
const ObservationSet*
matchObservations(PairLoop& L, int it)
{
  const ObservationSet& obs = L.matcher.match(BlockLinearization(L.pair.setup.source), L.target_pose,
                                              {L.control.stride(), L.control.skipMissed(it)});
  if (L.hooks.filter) {  // e.g. PCL's correspondence rejectors
    std::vector<char> keep(obs.size(), 1);
    L.hooks.filter(L.pair.setup.source.matrix(), obs, keep);
    const bool had_some = !obs.empty();
    L.matcher.keepOnly(keep);
    if (had_some && obs.empty()) {
      L.report.iterations = it - 1;
      fail(L.report, TerminationType::TOO_FEW_OBSERVATIONS,
           "the observation filter (e.g. PCL's correspondence rejectors) left none");
      return nullptr;
    }
  }
  return &obs;
}

// Enough observations to solve with; at the first iteration also the start's figures.
bool
observationsUsable(PairLoop& L, const ObservationSet& obs, int it)
{
  L.report.correspondences = obs.size();
  if (obs.empty() && it == 1) {
    noConjugatePoint(L.source, L.guess, L.target, L.pair.setup, L.report);
    return false;
  }
  if (tooFewObservations(obs.size(), it, L.settings, L.report))
    return false;
  if (it == 1) {
    L.pair.start_scale = robustScale(obs.distances());
    L.pair.start_correspondences = obs.size();
  }
  return true;
}

// Stage 5: log, then let the iteration control decide (extrapolate, freeze, stop).
Step
decide(PairLoop& L, const NormalEquations& ne, const ObservationSet& obs, int it)
{
  PairRun& pair = L.pair;
  IterationRecord rec = iterationRecord(it, ne, obs.size(), pair.sol);
  L.report.observations_used = ne.n;
  L.report.observations_rejected = obs.size() - ne.n;
  L.report.termination = TerminationType::MAX_ITERATIONS;
  const IterationControl::Decision next = L.control.next(pair.sol, pair.problem.scaling, it);
  pair.setup.source.values += next.extrapolation * pair.sol.dx;
  rec.extrapolated = next.extrapolation > 0.0;
  rec.parameters = pair.setup.source.values;
  L.report.log.push_back(rec);
  if (next.freeze)
    L.matcher.freeze();
  const bool stop = L.hooks.after_iteration && L.hooks.after_iteration(rec, pair.setup.source.matrix(), obs);
  // Converged while the annealed floor still set the cut: the estimate is the floor's, not
  // the estimator's. Go on while the floor keeps halving, until the estimator's own cut rules.
  const bool settled = next.converged && !L.weighting.floorBound() && !pair.reset;
  if (settled || stop) {
    L.report.termination = TerminationType::CONVERGED;
    return Step::CONVERGED;
  }
  return Step::NEXT;
}

// One iteration: match (stage 2), weight, normal equations and solve (stages 3–4), decide (5).
Step
iterate(PairLoop& L, int it)
{
  PairRun& pair = L.pair;
  if (it > 1) {  // the reach follows the fit (automatic_reach)
    L.matcher.setReach(L.control.reach(pair.sol.sigma0, pair.spacing));
    L.control.setCulling(L.matcher.culling());
  }
  const ObservationSet* matched = matchObservations(L, it);
  if (!matched || !observationsUsable(L, *matched, it))
    return Step::FAILED;
  const ObservationSet& obs = *matched;
  pair.eiv.update(pair.setup.source.values[SCALE], pair.sol.sigma0, meanSquaredGradient(obs));
  const SourceRows row{L.matcher, obs, pair.eiv};
  // Stages 3–4: robust weights (eq. 15), normal equations (eq. 8), solve (eqs. 9–11).
  const Eigen::VectorXd& p =
      L.weighting.compute(L.estimator, obs, row, pair.sol.sigma0, Matrix7d(pair.sol.qxx), it,
                          annealedCut(pair.guess_uncertainty, it));
  const NormalEquations ne = accumulateNormalEquations(row, p);
  const std::vector<bool> held = noiseDominatedParameters(pair, L.target, row, p, ne);
  if (!solveAndUpdate(pair, ne, held, it, L.settings, L.report))
    return Step::FAILED;
  return decide(L, ne, obs, it);
}

}  // namespace

AdjustmentReport
SurfaceMatchingCore::run(const std::vector<Eigen::Vector3d>& source, const std::vector<int>& source_indices,
                         const TargetSurface& target, const ConjugateRule& rule,
                         const RobustEstimator& estimator, const AdjustmentSettings& settings,
                         const Eigen::Matrix4d& guess)
{
  AdjustmentReport report;
  report.rule_name = rule.name();
  report.estimator_name = estimator.name();
  report.source_points = source.size();
  const std::string invalid = invalidInput(source, target, settings, guess);
  if (!invalid.empty())
    return fail(report, TerminationType::INVALID_INPUT, invalid);
  // Stage 1: parameter blocks and frames (the target's block is the identity).
  PairRun pair;
  if (!setUpPair(source, target, guess, settings, pair.setup, reduced_))
    return fail(report, TerminationType::NO_OVERLAP,
                "no source point falls over the target's extent under the initial guess");
  prepareRun(pair, target, settings, reduced_, report);
  const BlockLinearization target_pose(pair.setup.target);
  matcher_.reset(reduced_, target, rule, settings.max_correspondence_distance);
  IterationControl control(settings, reduced_.size(), matcher_.culling(), pair.spacing);
  PairLoop loop{source,   target,     estimator,   settings, guess, hooks_,
                matcher_, weighting_, target_pose, control,  pair,  report};
  for (int it = 1; it <= settings.max_iterations; ++it) {
    const Step step = iterate(loop, it);
    if (step == Step::FAILED)
      return report;
    if (step == Step::CONVERGED)
      break;
  }
  finish(pair, SourceRows{matcher_, matcher_.observations(), pair.eiv}, weighting_.weights(), settings,
         target, source_indices, report);
  return report;
}

}  // namespace pcl_ls3d
