#include <pcl_ls3d/adjustment/block_normal_equations.h>
#include <pcl_ls3d/adjustment/iteration_control.h>
#include <pcl_ls3d/adjustment/noise_floor.h>
#include <pcl_ls3d/strips/block_solve.h>
#include <pcl_ls3d/strips/overlap_matcher.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace strips {

namespace {

// σ_obs of the soft datum: the observations' robust scale in the first iteration.
double
robustScaleOf(const std::vector<OverlapContribution>& contributions)
{
  double s2 = 0.0;
  std::size_t n = 0;
  for (const OverlapContribution& c : contributions)
    for (const DirectionCounts* d : {&c.forward, &c.backward}) {
      s2 += d->robust_scale * d->robust_scale * static_cast<double>(d->observations);
      n += d->observations;
    }
  return n ? std::sqrt(s2 / static_cast<double>(n)) : 1.0;
}

BlockIterationRecord
record(const BlockState& state, const GaussMarkovSolution& sol,
       const std::vector<OverlapContribution>& contributions)
{
  BlockIterationRecord r;
  r.iteration = state.iteration;
  for (const OverlapContribution& c : contributions) {
    r.observations += c.forward.observations + c.backward.observations;
    r.used += c.forward.used + c.backward.used;
  }
  r.sigma0 = sol.sigma0;
  for (Eigen::Index k = 0; k + 7 <= sol.dx.size(); k += 7) {
    r.max_angle_change = std::max(r.max_angle_change, sol.dx.segment<3>(k + PHI).cwiseAbs().maxCoeff());
    r.max_translation_change = std::max(r.max_translation_change, sol.dx.segment<3>(k).norm());
    r.max_scale_change = std::max(r.max_scale_change, std::abs(sol.dx[k + SCALE]));
  }
  r.coarse = state.coarse;
  r.frozen = state.frozen;
  return r;
}

// Parameters the overlaps carry no information on beyond the noise of the surface normals
// (noise_floor.h), per strip: its diagonal block of the normal matrix against its noise floor.
std::vector<bool>
noiseFloorUndeterminable(const StripPlan& plan, const std::vector<OverlapContribution>& contributions,
                         const GaussMarkovProblem& problem)
{
  const std::size_t n = plan.strips.size();
  std::vector<Matrix7d> N(n, Matrix7d::Zero()), M = N;
  for (const OverlapContribution& c : contributions) {
    const auto i = static_cast<std::size_t>(c.i), j = static_cast<std::size_t>(c.j);
    N[i] += c.normal.N.topLeftCorner<7, 7>();
    N[j] += c.normal.N.bottomRightCorner<7, 7>();
    M[i] += c.noise_floor.topLeftCorner<7, 7>();
    M[j] += c.noise_floor.bottomRightCorner<7, 7>();
  }
  std::vector<bool> flagged;
  flagged.reserve(7 * n);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Index g = 7 * static_cast<Eigen::Index>(k);
    const std::vector<bool> strip = noiseDominated(N[k], M[k], problem.apriori_weights.segment<7>(g),
                                                   problem.scaling.segment<7>(g), kStripNoiseShare);
    flagged.insert(flagged.end(), strip.begin(), strip.end());
  }
  return flagged;
}

// Parameters under the noise floor are held at their start values: fixed for this solve and
// reported undeterminable. Returns their flags (7N).
std::vector<bool>
holdWeakParameters(const StripPlan& plan, const std::vector<OverlapContribution>& contributions,
                   BlockState& state, GaussMarkovProblem& problem)
{
  const std::vector<bool> weak = noiseFloorUndeterminable(plan, contributions, problem);
  const Eigen::VectorXd start =
      identityParameters().replicate(static_cast<Eigen::Index>(plan.strips.size()), 1);
  for (std::size_t g = 0; g < weak.size(); ++g)
    if (weak[g])
      state.values[g / 7][static_cast<Eigen::Index>(g % 7)] = start[static_cast<Eigen::Index>(g)];
  holdAtStart(weak, start, problem);
  return weak;
}

void
stop(BlockState& state, TerminationType type, const std::string& message)
{
  state.termination = type;
  state.message = message;
  state.phase = BlockState::Phase::DONE;
}

}  // namespace

std::vector<ParameterBlock>
BlockState::blocks(const StripPlan& plan) const
{
  std::vector<ParameterBlock> b = plan.initialBlocks(soft_sigma_obs > 0.0 ? soft_sigma_obs : 1.0);
  for (std::size_t k = 0; k < b.size() && k < values.size(); ++k)
    b[k].values = values[k];
  return b;
}

BlockState
initialState(const StripPlan& plan)
{
  BlockState s;
  s.values.assign(plan.strips.size(), identityParameters());
  const Eigen::Index u = 7 * static_cast<Eigen::Index>(plan.strips.size());
  s.qxx = Eigen::MatrixXd::Zero(u, u);
  s.fixed.assign(static_cast<std::size_t>(u), false);
  s.determinable.assign(static_cast<std::size_t>(u), false);
  s.coarse = plan.settings.adjustment.coarse_observations > 0;
  return s;
}

MatchInput
matchInput(const StripPlan& plan, const BlockState& state, int i, int j)
{
  MatchInput in;
  in.iteration = state.iteration + 1;
  in.coarse = state.coarse && state.phase == BlockState::Phase::ITERATE;
  in.frozen = state.frozen;
  in.sigma0 = state.sigma0;
  // The final pass of a rigid block also corrects the held-out scale column: its score test
  // (model_adequacy.h) would otherwise see the noise bias of that column as a scale.
  in.scale_free = plan.settings.model == ParameterModel::SIMILARITY_7 ||
                  (plan.settings.model == ParameterModel::RIGID_6 && plan.settings.test_held_out &&
                   state.phase == BlockState::Phase::EVALUATE);
  if (state.qxx.rows() == 7 * static_cast<Eigen::Index>(plan.strips.size()) && state.iteration > 0) {
    const Eigen::Index a = 7 * i, b = 7 * j;
    in.qxx.topLeftCorner<7, 7>() = state.qxx.block<7, 7>(a, a);
    in.qxx.topRightCorner<7, 7>() = state.qxx.block<7, 7>(a, b);
    in.qxx.bottomLeftCorner<7, 7>() = state.qxx.block<7, 7>(b, a);
    in.qxx.bottomRightCorner<7, 7>() = state.qxx.block<7, 7>(b, b);
  }
  return in;
}

void
solveIteration(const StripPlan& plan, const std::vector<OverlapContribution>& contributions,
               BlockState& state)
{
  const StripAdjustmentSettings& s = plan.settings;
  if (state.iteration == 0 && s.soft_datum)
    state.soft_sigma_obs = robustScaleOf(contributions);
  std::vector<OverlapContribution> sorted = contributions;  // sum in overlap order
  std::sort(sorted.begin(), sorted.end(),
            [](const OverlapContribution& a, const OverlapContribution& b) { return a.overlap < b.overlap; });
  BlockNormalEquations ne(static_cast<int>(plan.strips.size()));
  for (const OverlapContribution& c : sorted)
    ne.addOverlap(c.i, c.j, c.normal);
  if (ne.observations() == 0) {
    ++state.iteration;
    return stop(state, TerminationType::TOO_FEW_OBSERVATIONS,
                "no overlap has an observation: no overlap direction has " +
                    std::to_string(s.min_overlap_observations) +
                    " observed points (-min_obs), or none of the observed classes (-classes) has a "
                    "conjugate point on the other strip within -max_dist");
  }
  GaussMarkovProblem problem = plan.problem(state.blocks(plan));
  const std::vector<bool> weak = holdWeakParameters(plan, sorted, state, problem);
  GaussMarkovSolution sol = solveGaussMarkov(ne, problem);
  if (sol.ok)
    reportHeldUndeterminable(weak, sol);
  ++state.iteration;
  if (!sol.ok)
    return stop(state, TerminationType::SINGULAR, sol.message);
  if (sol.redundancy <= 0)
    return stop(state, TerminationType::TOO_FEW_OBSERVATIONS, "no redundancy (r = n - u <= 0)");
  for (std::size_t k = 0; k < state.values.size(); ++k) {
    state.values[k] += sol.dx.segment<7>(7 * static_cast<Eigen::Index>(k));
    if (!state.values[k].allFinite() || !(state.values[k][SCALE] > 0.0))
      return stop(state, TerminationType::DIVERGED,
                  "the estimate of strip " + plan.strips[k].name + " became non-finite");
  }
  state.sigma0 = sol.sigma0;
  state.qxx = sol.qxx;
  state.fixed = sol.fixed;
  state.determinable = sol.determinable;
  state.redundancy = sol.redundancy;
  state.observations = ne.observations();
  state.log.push_back(record(state, sol, sorted));
  state.termination = TerminationType::MAX_ITERATIONS;

  // The engine's iteration policy for all strips at once (advancePhase, iteration_control.h).
  IterationPhase phase{state.coarse, state.frozen};
  const bool converged = advancePhase(phase, sol, s.adjustment, state.iteration).converged;
  state.coarse = phase.coarse;
  state.frozen = phase.frozen;
  if (converged) {
    state.termination = TerminationType::CONVERGED;
    state.phase = BlockState::Phase::EVALUATE;
    return;
  }
  if (state.iteration >= s.adjustment.max_iterations) {
    state.phase = BlockState::Phase::EVALUATE;
    state.message = "iteration limit reached before the changes fell below the epsilons";
  }
}

}  // namespace strips
}  // namespace pcl_ls3d
