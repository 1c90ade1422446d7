#pragma once
/// \file strip_stages.h
/// \brief The strip adjustment as separate processes that exchange files in a work directory
///        (a cluster runs them as Slurm job arrays: scripts/slurm/strip_adjust.sbatch):
///          plan   — read the strips, footprints, overlap graph, datum, job list;
///          match  — one overlap: its observations at the current poses reduced to that
///                   overlap's normal-equation contribution (and, first and last, its
///                   discrepancy samples);
///          solve  — sum the contributions, solve, decide whether to iterate; after the final
///                   pass write the report and the maps;
///          apply  — write one corrected output file.
///        Every stage computes exactly what StripBlockAdjustment computes in one process, in the
///        same order, so both give the same numbers.

#include <pcl_ls3d/strips/strip_files.h>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace strips {

/// \brief Paths in a work directory.
struct WorkDir
{
  std::string root;

  std::string
  plan() const
  {
    return root + "/plan.json";
  }
  std::string
  state() const
  {
    return root + "/state.json";
  }
  std::string
  contribution(int job, int iteration) const
  {
    return root + "/contribution_" + std::to_string(job) + "_" + std::to_string(iteration) + ".bin";
  }
  std::string
  finalContribution(int job) const
  {
    return root + "/contribution_" + std::to_string(job) + "_final.bin";
  }
  std::string
  matcher(int job) const
  {
    return root + "/matcher_" + std::to_string(job) + ".bin";
  }
  std::string
  samples(int job) const
  {
    return root + "/samples_" + std::to_string(job) + ".bin";
  }
};

/// Stage plan: reads the inputs, plans, writes plan.json and the initial state. `request`
/// carries the settings, load options and output locations (its plan is filled here).
bool
stagePlan(const std::vector<std::string>& inputs, PlanFile request, const WorkDir& work, std::string& error);

/// Stage match for job `job` (0 ≤ job < number of used overlaps) in the state's next pass.
bool
stageMatch(const WorkDir& work, int job, std::string& error);

/// Stage solve: one solve (phase ITERATE) or, after the final pass, the report and the maps.
/// `phase` receives the state's phase afterwards: "iterate", "evaluate" or "done"; at "done",
/// `termination` (when given) the report's verdict, as a single-process run gives it.
bool
stageSolve(const WorkDir& work, std::string& phase, std::string& error,
           TerminationType* termination = nullptr);

/// Stage apply: writes output unit `unit` (see outputUnits()).
bool
stageApply(const WorkDir& work, int unit, std::string& error);

/// Number of match jobs and of output units of a planned work directory.
bool
stageCounts(const WorkDir& work, int& jobs, int& units, std::string& error);

/// The corrections of all strips as 4 × 4 matrices in file coordinates.
std::vector<Eigen::Matrix4d>
fileCorrections(const StripPlan& plan, const BlockState& state);

/// Writes the report JSON (when json_path is set) and the maps (when maps_dir is set) of a
/// finished adjustment; `written` receives the map files.
bool
writeReportAndMaps(const PlanFile& plan, const StripAdjustmentReport& report,
                   const std::vector<OverlapSamples>& samples, std::vector<std::string>& written,
                   std::string& error);

}  // namespace strips
}  // namespace pcl_ls3d
