// The strip block adjustment in one process: the stages of a distributed run, in memory.
#include <pcl_ls3d/estimators/robust_estimator.h>
#include <pcl_ls3d/strips/block_precision.h>
#include <pcl_ls3d/strips/overlap_matcher.h>
#include <pcl_ls3d/strips/strip_block_adjustment.h>

#include <pcl/common/time.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <functional>
#include <utility>

namespace pcl_ls3d {
namespace strips {

namespace {

// What one overlap keeps alive across the iterations of a single-process run.
struct OverlapWork
{
  int index = -1;  // into plan.overlaps
  OverlapSelection selection;
  std::unique_ptr<OverlapMatcher> matcher;
  std::unique_ptr<DiscrepancyEvaluator> evaluator;
};

std::string
format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

std::string
format(const char* fmt, ...)
{
  char buf[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof(buf), fmt, args);
  va_end(args);
  return buf;
}

using Say = std::function<void(const std::string&)>;

/// Stage "observations": per overlap its stable surfaces, thinned, in both directions, and the
/// matcher and discrepancy evaluator that keep them across the iterations.
std::vector<OverlapWork>
prepareOverlaps(const std::vector<Strip>& strips, const StripPlan& plan, const std::vector<int>& jobs,
                const Footprints& footprints, const StripAdjustmentSettings& settings,
                const ConjugateRule& rule, const RobustEstimator& estimator, const Say& say)
{
  std::vector<OverlapWork> work(jobs.size());
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    OverlapWork& w = work[k];
    w.index = jobs[k];
    const Overlap& o = plan.overlaps[static_cast<std::size_t>(w.index)];
    const auto i = static_cast<std::size_t>(o.i), j = static_cast<std::size_t>(o.j);
    w.selection = selectObservations(strips, o, footprints, settings);
    const double noise_i = stripNoise(*w.selection.backward.surface, footprints.density(i));
    const double noise_j = stripNoise(*w.selection.forward.surface, footprints.density(j));
    w.matcher = std::make_unique<OverlapMatcher>(w.selection, rule, estimator, settings, noise_i, noise_j);
    w.evaluator = std::make_unique<DiscrepancyEvaluator>(w.selection, settings.max_distance);
    const bool forward = directionWanted(w.selection.forward, true, settings);
    const bool backward = directionWanted(w.selection.backward, false, settings);
    say(format("overlap %zu of %zu (%s-%s): %zu + %zu observed points, spacing %.3g%s", k + 1, jobs.size(),
               strips[i].name.c_str(), strips[j].name.c_str(), w.selection.forward.points.size(),
               w.selection.backward.points.size(), w.selection.spacing,
               forward && backward ? ""
               : forward           ? "; one way: points of the first on the second"
               : backward          ? "; one way: points of the second on the first"
                                   : "; not matched: too few observed points"));
  }
  return work;
}

/// The two parameter blocks of an overlap's strips.
std::pair<const ParameterBlock&, const ParameterBlock&>
blocksOf(const std::vector<ParameterBlock>& blocks, const Overlap& o)
{
  return {blocks[static_cast<std::size_t>(o.i)], blocks[static_cast<std::size_t>(o.j)]};
}

/// A contribution labelled with its overlap, its strips and its observation spacing.
OverlapContribution
labelled(OverlapContribution c, const OverlapWork& w, const Overlap& o)
{
  c.overlap = w.index;
  c.i = o.i;
  c.j = o.j;
  c.spacing = w.selection.spacing;
  return c;
}

/// Discrepancies of every overlap at the initial poses.
void
discrepanciesBefore(const std::vector<OverlapWork>& work, const StripPlan& plan, const BlockState& state,
                    std::vector<OverlapSamples>& samples)
{
  const std::vector<ParameterBlock> blocks = state.blocks(plan);
  for (const OverlapWork& w : work) {
    const auto [bi, bj] = blocksOf(blocks, plan.overlaps[static_cast<std::size_t>(w.index)]);
    samples[static_cast<std::size_t>(w.index)].before = w.evaluator->evaluate(bi, bj);
  }
}

/// Stage "iterate": match every overlap at the current poses, solve, decide (Zuo §4), until
/// the state leaves its iterating phase.
void
iterate(std::vector<OverlapWork>& work, const StripPlan& plan, BlockState& state, const pcl::StopWatch& watch,
        const Say& say)
{
  while (state.phase == BlockState::Phase::ITERATE) {
    const std::vector<ParameterBlock> blocks = state.blocks(plan);
    std::vector<OverlapContribution> contributions;
    for (OverlapWork& w : work) {
      const Overlap& o = plan.overlaps[static_cast<std::size_t>(w.index)];
      const auto [bi, bj] = blocksOf(blocks, o);
      contributions.push_back(
          labelled(w.matcher->contribute(bi, bj, matchInput(plan, state, o.i, o.j)), w, o));
    }
    solveIteration(plan, contributions, state);
    if (!state.log.empty() && state.log.back().iteration == state.iteration) {
      const BlockIterationRecord& r = state.log.back();
      say(format(
          "iteration %d: sigma0 %.4g, %zu of %zu observations used, max change %.2e rad / %.2e%s%s, %.1f s",
          r.iteration, r.sigma0, r.used, r.observations, r.max_angle_change, r.max_translation_change,
          r.coarse ? ", coarse" : "", r.frozen ? ", frozen" : "", watch.getTimeSeconds()));
    }
  }
}

/// Stage "evaluate": a last pass at the adjusted poses gives the precision cells and the
/// discrepancies after (nothing when the iterations did not end in the evaluating phase).
std::vector<OverlapContribution>
finalPass(std::vector<OverlapWork>& work, const StripPlan& plan, BlockState& state,
          std::vector<OverlapSamples>& samples)
{
  std::vector<OverlapContribution> final_pass;
  if (state.phase != BlockState::Phase::EVALUATE)
    return final_pass;
  const std::vector<ParameterBlock> blocks = state.blocks(plan);
  for (OverlapWork& w : work) {
    const Overlap& o = plan.overlaps[static_cast<std::size_t>(w.index)];
    const auto [bi, bj] = blocksOf(blocks, o);
    final_pass.push_back(
        labelled(w.matcher->evaluate(bi, bj, matchInput(plan, state, o.i, o.j), plan.precision_cell), w, o));
    OverlapSamples& s = samples[static_cast<std::size_t>(w.index)];
    s.after = w.evaluator->evaluate(bi, bj);
    s.noise = w.evaluator->ownNoise(bi, bj);
  }
  state.phase = BlockState::Phase::DONE;
  return final_pass;
}

}  // namespace

StripBlockAdjustment::StripBlockAdjustment() = default;
StripBlockAdjustment::~StripBlockAdjustment() = default;

bool
StripBlockAdjustment::run(const std::vector<Strip>& strips, StripAdjustmentReport& report, std::string& error)
{
  const Say say = [this](const std::string& line) {
    if (progress_)
      progress_(line);
  };
  pcl::StopWatch watch;
  std::vector<double> timings;
  // Stage "plan": footprints, overlap graph, datum.
  Footprints footprints;
  if (!makePlan(strips, settings_, plan_, error, &footprints))
    return false;
  plan_.block_origin = block_origin_;
  const RobustEstimator::Ptr estimator = makeRobustEstimator(settings_.estimator);
  const ConjugateRule::Ptr rule = makeConjugateRule(settings_.rule);
  const std::vector<int> jobs = plan_.jobs();
  say(format("plan: %zu strips, %zu overlaps used of %zu, footprint cell %.3g", strips.size(), jobs.size(),
             plan_.overlaps.size(), plan_.grid.cell));
  timings.push_back(watch.getTimeSeconds());

  std::vector<OverlapWork> work =
      prepareOverlaps(strips, plan_, jobs, footprints, settings_, *rule, *estimator, say);
  timings.push_back(watch.getTimeSeconds() - timings.back());

  samples_.assign(plan_.overlaps.size(), OverlapSamples());
  BlockState state = initialState(plan_);
  discrepanciesBefore(work, plan_, state, samples_);

  const double t_iterate = watch.getTimeSeconds();
  iterate(work, plan_, state, watch, say);
  timings.push_back(watch.getTimeSeconds() - t_iterate);

  const double t_eval = watch.getTimeSeconds();
  const std::vector<OverlapContribution> final_pass = finalPass(work, plan_, state, samples_);
  report = makeReport(plan_, state, final_pass, samples_);
  timings.push_back(watch.getTimeSeconds() - t_eval);
  report.timings_s = timings;
  return true;
}

Eigen::Matrix4d
blockTransformation(const ParameterBlock& block)
{
  // The block maps local coordinates (block − o_k, o_k = output origin) into block coordinates.
  Eigen::Matrix4d to_local = Eigen::Matrix4d::Identity();
  to_local.topRightCorner<3, 1>() = -block.output_origin + block.input_origin;
  return block.matrix() * to_local;
}

}  // namespace strips
}  // namespace pcl_ls3d
