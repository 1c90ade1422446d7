// The test of the parameters a strip model holds out (model_adequacy.h).
#include <pcl_ls3d/adjustment/block_normal_equations.h>
#include <pcl_ls3d/adjustment/noise_floor.h>
#include <pcl_ls3d/adjustment/omitted_parameters.h>
#include <pcl_ls3d/stats/descriptive.h>
#include <pcl_ls3d/strips/block_precision.h>
#include <pcl_ls3d/strips/model_adequacy.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace pcl_ls3d {
namespace strips {

namespace {

// The normal equations of the final pass, summed in overlap order as the solve sums them.
BlockNormalEquations
finalNormalEquations(const StripPlan& plan, std::vector<OverlapContribution> final_pass)
{
  std::sort(final_pass.begin(), final_pass.end(),
            [](const OverlapContribution& a, const OverlapContribution& b) { return a.overlap < b.overlap; });
  BlockNormalEquations ne(static_cast<int>(plan.strips.size()));
  for (const OverlapContribution& c : final_pass)
    ne.addOverlap(c.i, c.j, c.normal);
  return ne;
}

// The model with the held-out scales freed: which parameters it adds, and its a-priori weights
// and estimated flags (a soft datum observes the freed scale as -params 7 would: σ_obs² / σ_m²).
struct FreedModel
{
  std::vector<int> omitted;
  Eigen::VectorXd weights;
  std::vector<bool> estimated;
};

// Would strip k's freed scale be determinable? The solve's noise-floor test (noise_floor.h) on
// the strip's block of the final pass with the scale free: a scale whose information is no more
// than the surface normals' noise would be held by -params 7 too, and testing it would read the
// horizontal misfit the held parameters leave as a scale.
bool
freedScaleDeterminable(const std::vector<OverlapContribution>& final_pass, const GaussMarkovProblem& problem,
                       std::size_t k, double weight)
{
  Matrix7d N = Matrix7d::Zero(), M = Matrix7d::Zero();
  for (const OverlapContribution& c : final_pass) {
    if (static_cast<std::size_t>(c.i) == k) {
      N += c.normal.N.topLeftCorner<7, 7>();
      M += c.noise_floor.topLeftCorner<7, 7>();
    }
    if (static_cast<std::size_t>(c.j) == k) {
      N += c.normal.N.bottomRightCorner<7, 7>();
      M += c.noise_floor.bottomRightCorner<7, 7>();
    }
  }
  const Eigen::Index g = 7 * static_cast<Eigen::Index>(k);
  Vector7d weights = problem.apriori_weights.segment<7>(g);
  weights[SCALE] = weight;
  return !noiseDominated(N, M, weights, problem.scaling.segment<7>(g), kStripNoiseShare)[SCALE];
}

FreedModel
freedModel(const StripPlan& plan, const BlockState& state, const GaussMarkovProblem& problem,
           const std::vector<OverlapContribution>& final_pass, std::string& undeterminable)
{
  FreedModel f;
  f.weights = problem.apriori_weights;
  f.estimated = state.determinable;
  for (std::size_t k = 0; k < plan.strips.size(); ++k) {
    const std::size_t g = 7 * k + SCALE;
    if (plan.strips[k].reference || plan.strips[k].part < 0 || !state.fixed[g])
      continue;
    const double weight =
        plan.settings.soft_datum ? std::pow(state.soft_sigma_obs / plan.settings.soft_sigmas[SCALE], 2) : 0.0;
    if (!freedScaleDeterminable(final_pass, problem, k, weight)) {
      undeterminable += (undeterminable.empty() ? "" : ", ") + plan.strips[k].name;
      continue;
    }
    f.omitted.push_back(static_cast<int>(g));
    f.estimated[g] = true;
    f.weights[static_cast<Eigen::Index>(g)] = weight;
  }
  return f;
}

// Soft a-priori weights of the freed model's estimated parameters (zero elsewhere).
Eigen::VectorXd
softWeights(const FreedModel& f)
{
  Eigen::VectorXd w = Eigen::VectorXd::Zero(f.weights.size());
  for (Eigen::Index p = 0; p < w.size(); ++p)
    if (f.estimated[static_cast<std::size_t>(p)] && f.weights[p] > 0.0 && std::isfinite(f.weights[p]))
      w[p] = f.weights[p];
  return w;
}

// Var(AᵀPv) for the freed model's residuals v + a·step and leverage q: the spatial sandwich's
// middle term when the report's σ come from it, else the formal σ0² (N + P_e) — always the
// variance behind the report's own σ.
MiddleTermFn
middleTerm(const BlockState& state, const std::vector<OverlapContribution>& final_pass,
           const Eigen::MatrixXd& N, const FreedModel& freed, bool sandwich)
{
  if (sandwich)
    return [&](const Eigen::VectorXd& step, const Eigen::MatrixXd& q) {
      return blockMiddleTerm(final_pass, q, state.sigma0, freed.weights, freed.estimated, &step);
    };
  return [&](const Eigen::VectorXd&, const Eigen::MatrixXd&) {
    return Eigen::MatrixXd(state.sigma0 * state.sigma0 *
                           (N + Eigen::MatrixXd(softWeights(freed).asDiagonal())));
  };
}

// A strip's own noise: the median σMAD of its own discrepancies over its evaluated overlaps.
double
ownNoiseOf(const StripAdjustmentReport& report, int k)
{
  std::vector<double> noise;
  for (const OverlapResult& o : report.overlaps) {
    if (!o.used)
      continue;
    if (o.i == k && o.noise_i.count > 0)
      noise.push_back(o.noise_i.sigma_mad);
    if (o.j == k && o.noise_j.count > 0)
      noise.push_back(o.noise_j.sigma_mad);
  }
  return noise.empty() ? report.sigma0 : stats::medianHigh(std::move(noise));
}

// Why the block is not tested (empty: it is).
std::string
notTestable(const StripPlan& plan, const BlockState& state,
            const std::vector<OverlapContribution>& final_pass)
{
  if (!plan.settings.test_held_out || std::isinf(plan.settings.adjustment.held_out_z))
    return "switched off";
  if (plan.settings.model != ParameterModel::RIGID_6)
    return plan.settings.model == ParameterModel::SIMILARITY_7
               ? "nothing held out (7 parameters)"
               : "only the rigid model's held-out scale is tested (-params " +
                     parameterModelName(plan.settings.model) + ")";
  if (final_pass.empty() || state.redundancy <= 0 || !(state.sigma0 > 0.0))
    return "no final evaluation";
  return {};
}

// One strip's held-out parameter with its effect over the strip, its own noise and the flags.
HeldOutParameter
heldOutResult(const StripPlan& plan, const StripAdjustmentReport& report, const OmittedParameter& p)
{
  const int k = p.index / 7;
  HeldOutParameter h;
  h.parameter = p.index % 7;
  h.estimate = p.estimate;
  h.sigma = p.sigma;
  h.sigma_formal = p.sigma_formal;
  h.z = p.z;
  h.effect =
      std::abs(p.estimate) * (h.parameter >= PHI ? plan.strips[static_cast<std::size_t>(k)].radius : 1.0);
  h.noise = ownNoiseOf(report, k);
  h.significant = std::abs(h.z) > plan.settings.adjustment.held_out_z;
  h.flagged = h.significant && h.effect > plan.settings.adjustment.held_out_noise_factor * h.noise;
  return h;
}

}  // namespace

void
testHeldOutParameters(const StripPlan& plan, const BlockState& state,
                      const std::vector<OverlapContribution>& final_pass, StripAdjustmentReport& report)
{
  HeldOutTest& t = report.held_out;
  t.note = notTestable(plan, state, final_pass);
  if (!t.note.empty())
    return;
  const GaussMarkovProblem problem = plan.problem(state.blocks(plan));
  std::string skipped;
  const FreedModel freed = freedModel(plan, state, problem, final_pass, skipped);
  if (freed.omitted.empty()) {
    t.note = "no strip's scale is determinable from its overlaps";
    return;
  }
  const BlockNormalEquations ne = finalNormalEquations(plan, final_pass);
  const Eigen::MatrixXd N = ne.denseMatrix();
  const Eigen::VectorXd soft = softWeights(freed);
  // AᵀPv at the final pose with the a-priori part P_e (X − L_e), which the last solve made ~0
  // for the estimated parameters (and is 0 for the freed scales, still at m = 1).
  const Eigen::VectorXd gradient = ne.rhs() + soft.cwiseProduct(problem.current - problem.apriori_values);
  const bool sandwich = report.precision_model.rfind("spatial sandwich", 0) == 0;
  const OmittedParameterTest test =
      testOmittedParameters(N + Eigen::MatrixXd(soft.asDiagonal()), gradient, state.qxx,
                            middleTerm(state, final_pass, N, freed, sandwich), state.sigma0, freed.omitted);
  if (!test.ok) {
    t.note = test.message;
    return;
  }
  t.tested = true;
  t.note = "the scale of each strip, score test with the " + report.precision_model + " variance" +
           (skipped.empty() ? "" : "; not tested, the scale undeterminable from its overlaps: " + skipped);
  t.statistic = test.statistic;
  t.dof = static_cast<int>(test.parameters.size());
  for (const OmittedParameter& p : test.parameters) {
    const HeldOutParameter h = heldOutResult(plan, report, p);
    t.significant += h.significant ? 1 : 0;
    t.flagged += h.flagged ? 1 : 0;
    report.strips[static_cast<std::size_t>(p.index / 7)].held_out.push_back(h);
  }
}

void
confirmModel(StripAdjustmentReport& report)
{
  const TerminationType t = report.termination;
  if (report.held_out.flagged == 0 ||
      (t != TerminationType::CONVERGED && t != TerminationType::MAX_ITERATIONS &&
       t != TerminationType::UNRELIABLE))
    return;
  std::string strips;
  for (const StripResult& s : report.strips)
    for (const HeldOutParameter& h : s.held_out) {
      if (!h.flagged)
        continue;
      char buf[256];
      std::snprintf(buf, sizeof(buf),
                    "%s (m-1 %+.1f ppm +- %.1f, z %.1f, moves its edge by %.3g; own noise %.3g)",
                    s.name.c_str(), 1e6 * h.estimate, 1e6 * h.sigma, h.z, h.effect, h.noise);
      strips += (strips.empty() ? "" : ", ") + std::string(buf);
    }
  report.termination = TerminationType::UNRELIABLE;
  report.message += std::string(report.message.empty() ? "" : "; ") +
                    "NOT CONFIRMED: the rigid model holds out a scale the overlaps ask for on " +
                    std::to_string(report.held_out.flagged) + " strip(s): " + strips +
                    ": free the scale with -params 7";
}

}  // namespace strips
}  // namespace pcl_ls3d
