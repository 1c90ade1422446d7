// The distributed stages (strip_stages.h).
#include <pcl_ls3d/estimators/robust_estimator.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/strips/overlap_matcher.h>
#include <pcl_ls3d/strips/report_output.h>
#include <pcl_ls3d/strips/strip_maps.h>
#include <pcl_ls3d/strips/strip_stages.h>

#include <filesystem>
#include <fstream>

namespace pcl_ls3d {
namespace strips {

namespace fs = std::filesystem;

namespace {

bool
readBoth(const WorkDir& work, PlanFile& plan, BlockState& state, std::string& error)
{
  return readPlanFile(work.plan(), plan, error) && readState(work.state(), state, error);
}

// The two strips of an overlap, re-read with the plan's origins, their footprints on the plan's
// grid and the overlap's cells (indices 0 and 1 inside this pair).
struct PairData
{
  std::vector<Strip> strips;
  Footprints footprints;
  Overlap overlap;
};

bool
loadPair(const PlanFile& f, const Overlap& o, PairData& pair, std::string& error)
{
  pair.strips.resize(2);
  for (int k = 0; k < 2; ++k) {
    const int s = k == 0 ? o.i : o.j;
    if (!loadStrip(f.inputs, f.sources[static_cast<std::size_t>(s)], f.plan.block_origin, f.load,
                   pair.strips[static_cast<std::size_t>(k)], error))
      return false;
  }
  pair.footprints = Footprints::build(pair.strips, f.plan.grid);
  const std::vector<Overlap> found = findOverlaps(pair.footprints, 0.0);
  if (found.size() != 1 || found[0].common_cells != o.common_cells) {
    error = "the strips of overlap " + f.plan.strips[static_cast<std::size_t>(o.i)].name + "-" +
            f.plan.strips[static_cast<std::size_t>(o.j)].name + " changed since the plan";
    return false;
  }
  pair.overlap = found[0];
  return true;
}

const char*
phaseName(BlockState::Phase p)
{
  return p == BlockState::Phase::ITERATE ? "iterate" : p == BlockState::Phase::EVALUATE ? "evaluate" : "done";
}

// The overlap that match job `job` works on; false (`error` says why) when there is no such
// job or the adjustment is finished.
bool
jobOverlap(const PlanFile& f, const BlockState& state, int job, int& index, std::string& error)
{
  const std::vector<int> jobs = f.plan.jobs();
  if (job < 0 || static_cast<std::size_t>(job) >= jobs.size()) {
    error = "match job " + std::to_string(job) + " does not exist (" + std::to_string(jobs.size()) + " jobs)";
    return false;
  }
  if (state.phase == BlockState::Phase::DONE) {
    error = "the adjustment is finished; nothing to match";
    return false;
  }
  index = jobs[static_cast<std::size_t>(job)];
  return true;
}

// The matcher's memory from the job's previous run (none before the first iteration).
bool
restoreMatcher(const WorkDir& work, int job, const BlockState& state, OverlapMatcher& matcher,
               std::string& error)
{
  if (state.iteration == 0)
    return true;
  std::array<PairMatcher::State, 2> memory;
  if (!readMatcherState(work.matcher(job), memory, error) || !matcher.restore(std::move(memory))) {
    error =
        error.empty() ? "matcher state of job " + std::to_string(job) + " does not fit its points" : error;
    return false;
  }
  return true;
}

// The overlap's contribution at the strips' poses: its normal equations while iterating (the
// discrepancies before, at the first iteration), its figures and the discrepancies after at
// evaluation.
bool
contributeOverlap(const WorkDir& work, int job, const PlanFile& f, const BlockState& state, const Overlap& o,
                  const OverlapSelection& selection, OverlapMatcher& matcher, OverlapContribution& c,
                  std::string& error)
{
  DiscrepancyEvaluator evaluator(selection, f.plan.settings.max_distance);
  const std::vector<ParameterBlock> blocks = state.blocks(f.plan);
  const ParameterBlock &bi = blocks[static_cast<std::size_t>(o.i)],
                       &bj = blocks[static_cast<std::size_t>(o.j)];
  const MatchInput in = matchInput(f.plan, state, o.i, o.j);
  OverlapSamples samples;
  if (state.phase == BlockState::Phase::ITERATE) {
    if (state.iteration == 0) {
      samples.before = evaluator.evaluate(bi, bj);
      if (!writeSamples(work.samples(job), samples, error))
        return false;
    }
    c = matcher.contribute(bi, bj, in);
    return true;
  }
  c = matcher.evaluate(bi, bj, in, f.plan.precision_cell);
  if (!readSamples(work.samples(job), samples, error))
    return false;
  samples.after = evaluator.evaluate(bi, bj);
  samples.noise = evaluator.ownNoise(bi, bj);
  return writeSamples(work.samples(job), samples, error);
}

}  // namespace

std::vector<Eigen::Matrix4d>
fileCorrections(const StripPlan& plan, const BlockState& state)
{
  std::vector<Eigen::Matrix4d> out;
  Eigen::Matrix4d in = Eigen::Matrix4d::Identity(), back = Eigen::Matrix4d::Identity();
  in.topRightCorner<3, 1>() = -plan.block_origin;
  back.topRightCorner<3, 1>() = plan.block_origin;
  for (const ParameterBlock& b : state.blocks(plan)) {
    const bool identity = b.values == identityParameters();
    out.push_back(identity ? Eigen::Matrix4d::Identity()
                           : Eigen::Matrix4d(back * blockTransformation(b) * in));
  }
  return out;
}

bool
stagePlan(const std::vector<std::string>& inputs, PlanFile f, const WorkDir& work, std::string& error)
{
  LoadedStrips block;
  if (!loadStrips(inputs, f.load, block, error))
    return false;
  const StripAdjustmentSettings settings = f.plan.settings;  // makePlan resets f.plan
  if (!makePlan(block.strips, settings, f.plan, error))
    return false;
  f.plan.block_origin = block.block_origin;
  f.inputs = block.inputs;
  f.sources = block.sources;
  f.crs_wkt = block.crs_wkt;
  f.unassigned = block.unassigned;
  f.load_notes = block.notes;
  std::error_code ec;
  fs::create_directories(work.root, ec);
  return writePlanFile(work.plan(), f, error) && writeState(work.state(), initialState(f.plan), error);
}

bool
stageMatch(const WorkDir& work, int job, std::string& error)
{
  PlanFile f;
  BlockState state;
  int index = -1;
  if (!readBoth(work, f, state, error) || !jobOverlap(f, state, job, index, error))
    return false;
  const Overlap& o = f.plan.overlaps[static_cast<std::size_t>(index)];
  PairData pair;
  if (!loadPair(f, o, pair, error))
    return false;
  const StripAdjustmentSettings& s = f.plan.settings;
  const OverlapSelection selection = selectObservations(pair.strips, pair.overlap, pair.footprints, s);
  const RobustEstimator::Ptr estimator = makeRobustEstimator(s.estimator);
  const ConjugateRule::Ptr rule = makeConjugateRule(s.rule);
  OverlapMatcher matcher(selection, *rule, *estimator, s,
                         stripNoise(*selection.backward.surface, pair.footprints.density(0)),
                         stripNoise(*selection.forward.surface, pair.footprints.density(1)));
  OverlapContribution c;
  if (!restoreMatcher(work, job, state, matcher, error) ||
      !contributeOverlap(work, job, f, state, o, selection, matcher, c, error))
    return false;
  c.overlap = index;
  c.i = o.i;
  c.j = o.j;
  c.spacing = selection.spacing;
  const std::string path = state.phase == BlockState::Phase::ITERATE
                               ? work.contribution(job, state.iteration + 1)
                               : work.finalContribution(job);
  return writeContribution(path, c, error) && writeMatcherState(work.matcher(job), matcher.state(), error);
}

bool
stageSolve(const WorkDir& work, std::string& phase, std::string& error, TerminationType* termination)
{
  PlanFile f;
  BlockState state;
  if (!readBoth(work, f, state, error))
    return false;
  const std::vector<int> jobs = f.plan.jobs();
  std::vector<OverlapContribution> contributions(jobs.size());
  if (state.phase == BlockState::Phase::DONE) {
    phase = "done";
    return true;  // the verdict was given when the report was made
  }
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    const std::string path = state.phase == BlockState::Phase::ITERATE
                                 ? work.contribution(static_cast<int>(k), state.iteration + 1)
                                 : work.finalContribution(static_cast<int>(k));
    if (!readContribution(path, contributions[k], error))
      return false;
  }
  if (state.phase == BlockState::Phase::ITERATE) {
    solveIteration(f.plan, contributions, state);
    phase = phaseName(state.phase);
    if (termination && state.phase == BlockState::Phase::DONE)  // stopped: singular, too few
      *termination = state.termination;
    return writeState(work.state(), state, error);
  }
  // Final pass done: report and maps.
  std::vector<OverlapSamples> samples(f.plan.overlaps.size());
  for (std::size_t k = 0; k < jobs.size(); ++k)
    if (!readSamples(work.samples(static_cast<int>(k)), samples[static_cast<std::size_t>(jobs[k])], error))
      return false;
  state.phase = BlockState::Phase::DONE;
  const StripAdjustmentReport report = makeReport(f.plan, state, contributions, samples);
  if (termination)
    *termination = report.termination;
  std::vector<std::string> written;
  if (!writeReportAndMaps(f, report, samples, written, error))
    return false;
  phase = "done";
  return writeState(work.state(), state, error);
}

bool
stageCounts(const WorkDir& work, int& jobs, int& units, std::string& error)
{
  PlanFile f;
  if (!readPlanFile(work.plan(), f, error))
    return false;
  jobs = static_cast<int>(f.plan.jobs().size());
  units =
      f.output_dir.empty() ? 0 : static_cast<int>(outputUnits(f.block(), f.output_dir, f.keep_files).size());
  return true;
}

bool
stageApply(const WorkDir& work, int unit, std::string& error)
{
  PlanFile f;
  BlockState state;
  if (!readBoth(work, f, state, error))
    return false;
  if (state.phase != BlockState::Phase::DONE) {
    error = "the adjustment has not finished (phase " + std::string(phaseName(state.phase)) + ")";
    return false;
  }
  const LoadedStrips block = f.block();
  const std::vector<OutputUnit> units = outputUnits(block, f.output_dir, f.keep_files);
  if (unit < 0 || static_cast<std::size_t>(unit) >= units.size()) {
    error = "output unit " + std::to_string(unit) + " does not exist (" + std::to_string(units.size()) +
            " units)";
    return false;
  }
  std::error_code ec;
  fs::create_directories(f.output_dir, ec);
  return writeCorrected(block, units[static_cast<std::size_t>(unit)], fileCorrections(f.plan, state), error);
}

bool
writeReportAndMaps(const PlanFile& f, const StripAdjustmentReport& report,
                   const std::vector<OverlapSamples>& samples, std::vector<std::string>& written,
                   std::string& error)
{
  if (!f.json_path.empty()) {
    std::ofstream out(f.json_path, std::ios::trunc);
    const double heights = maps::planUnitsPerHeightUnit(f.crs_wkt);  // the block's CRS
    if (!out || !(out << reportJson(report, 2, heights) << '\n') || !out.flush()) {
      error = "cannot write " + f.json_path;
      return false;
    }
  }
  if (f.maps_dir.empty())
    return true;
  std::error_code ec;
  fs::create_directories(f.maps_dir, ec);
  StripMapSettings m;
  m.inner = f.band_inner;
  m.outer = f.band_outer;
  m.crs_wkt = f.crs_wkt;
  m.format = f.map_format;
  return writeStripMaps(report, f.plan, samples, f.maps_dir, m, written, error);
}

}  // namespace strips
}  // namespace pcl_ls3d
