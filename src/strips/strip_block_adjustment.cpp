// The strip block adjustment in one process: the stages of a distributed run, in memory.
#include <pcl_ls3d/estimators/robust_estimator.h>
#include <pcl_ls3d/strips/block_precision.h>
#include <pcl_ls3d/strips/overlap_matcher.h>
#include <pcl_ls3d/strips/strip_block_adjustment.h>

#include <pcl/common/time.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>

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

}  // namespace

StripBlockAdjustment::StripBlockAdjustment() = default;
StripBlockAdjustment::~StripBlockAdjustment() = default;

bool
StripBlockAdjustment::run(const std::vector<Strip>& strips, StripAdjustmentReport& report,
                          std::string& error)
{
  auto say = [this](const std::string& line) {
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
  const RobustEstimator::Ptr estimator = parseRobustEstimator(settings_.estimator, &error);
  const ConjugateRule::Ptr rule = makeConjugateRule(settings_.rule);
  const std::vector<int> jobs = plan_.jobs();
  say(format("plan: %zu strips, %zu overlaps used of %zu, footprint cell %.3g", strips.size(),
             jobs.size(), plan_.overlaps.size(), plan_.grid.cell));
  timings.push_back(watch.getTimeSeconds());

  // Observations per overlap (stable surfaces, thinned, both directions) and their matchers.
  std::vector<OverlapWork> work(jobs.size());
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    OverlapWork& w = work[k];
    w.index = jobs[k];
    const Overlap& o = plan_.overlaps[static_cast<std::size_t>(w.index)];
    w.selection = selectObservations(strips, o, footprints, settings_);
    const double noise_i = stripNoise(*w.selection.backward.surface, footprints.density(static_cast<std::size_t>(o.i)));
    const double noise_j = stripNoise(*w.selection.forward.surface, footprints.density(static_cast<std::size_t>(o.j)));
    w.matcher = std::make_unique<OverlapMatcher>(w.selection, *rule, *estimator, settings_, noise_i, noise_j);
    w.evaluator = std::make_unique<DiscrepancyEvaluator>(w.selection, settings_.max_distance);
    say(format("overlap %zu of %zu (%s-%s): %zu + %zu observed points, spacing %.3g", k + 1, jobs.size(),
               strips[static_cast<std::size_t>(o.i)].name.c_str(), strips[static_cast<std::size_t>(o.j)].name.c_str(),
               w.selection.forward.points.size(), w.selection.backward.points.size(), w.selection.spacing));
  }
  timings.push_back(watch.getTimeSeconds() - timings.back());

  // Discrepancies before adjustment.
  samples_.assign(plan_.overlaps.size(), OverlapSamples());
  BlockState state = initialState(plan_);
  {
    const std::vector<ParameterBlock> blocks = state.blocks(plan_);
    for (OverlapWork& w : work) {
      const Overlap& o = plan_.overlaps[static_cast<std::size_t>(w.index)];
      samples_[static_cast<std::size_t>(w.index)].before =
          w.evaluator->evaluate(blocks[static_cast<std::size_t>(o.i)], blocks[static_cast<std::size_t>(o.j)]);
    }
  }

  // Iterations: match every overlap at the current poses, solve, decide (Zuo §4).
  const double t_iterate = watch.getTimeSeconds();
  while (state.phase == BlockState::Phase::ITERATE) {
    const std::vector<ParameterBlock> blocks = state.blocks(plan_);
    std::vector<OverlapContribution> contributions;
    for (OverlapWork& w : work) {
      const Overlap& o = plan_.overlaps[static_cast<std::size_t>(w.index)];
      OverlapContribution c = w.matcher->contribute(blocks[static_cast<std::size_t>(o.i)], blocks[static_cast<std::size_t>(o.j)],
                                                    matchInput(plan_, state, o.i, o.j));
      c.overlap = w.index;
      c.i = o.i;
      c.j = o.j;
      c.spacing = w.selection.spacing;
      contributions.push_back(std::move(c));
    }
    solveIteration(plan_, contributions, state);
    if (!state.log.empty() && state.log.back().iteration == state.iteration) {
      const BlockIterationRecord& r = state.log.back();
      say(format("iteration %d: sigma0 %.4g, %zu of %zu observations used, max change %.2e rad / %.2e%s%s, %.1f s",
                 r.iteration, r.sigma0, r.used, r.observations, r.max_angle_change, r.max_translation_change,
                 r.coarse ? ", coarse" : "", r.frozen ? ", frozen" : "", watch.getTimeSeconds()));
    }
  }
  timings.push_back(watch.getTimeSeconds() - t_iterate);

  // Final pass at the adjusted poses: precision cells and discrepancies after.
  const double t_eval = watch.getTimeSeconds();
  std::vector<OverlapContribution> final_pass;
  if (state.phase == BlockState::Phase::EVALUATE) {
    const std::vector<ParameterBlock> blocks = state.blocks(plan_);
    for (OverlapWork& w : work) {
      const Overlap& o = plan_.overlaps[static_cast<std::size_t>(w.index)];
      const ParameterBlock &bi = blocks[static_cast<std::size_t>(o.i)], &bj = blocks[static_cast<std::size_t>(o.j)];
      MatchInput in = matchInput(plan_, state, o.i, o.j);
      OverlapContribution c = w.matcher->evaluate(bi, bj, in, plan_.precision_cell);
      c.overlap = w.index;
      c.i = o.i;
      c.j = o.j;
      c.spacing = w.selection.spacing;
      final_pass.push_back(std::move(c));
      OverlapSamples& s = samples_[static_cast<std::size_t>(w.index)];
      s.after = w.evaluator->evaluate(bi, bj);
      s.noise = w.evaluator->ownNoise(bi, bj);
    }
    state.phase = BlockState::Phase::DONE;
  }
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
