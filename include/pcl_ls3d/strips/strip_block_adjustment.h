#pragma once
/// \file strip_block_adjustment.h
/// \brief Simultaneous block adjustment of N airborne LiDAR strips on the LS3D engine (Zuo et
///        al. 2012, §3): one Gauss–Markov adjustment of all strips' similarity parameters from
///        conjugate points between the stable surfaces of every overlap, both directions, with
///        re-association, robust weights and iteration control as in LS3D; honest σ per strip;
///        discrepancies per overlap before and after. The stages (plan → match per overlap →
///        solve → … → final evaluation) are the ones a distributed run executes as separate
///        processes (strip_files.h); this class runs them in one process.

#include <pcl_ls3d/strips/strip.h>
#include <pcl_ls3d/strips/strip_adjustment_report.h>
#include <pcl_ls3d/strips/strip_plan.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace strips {

/// \brief Samples behind the maps of one overlap (block coordinates).
struct OverlapSamples
{
  DiscrepancySamples before, after;
  std::array<DiscrepancySamples, 2> noise;  ///< own noise of strips i and j
};

/// Progress lines ("overlap 3 of 21 prepared", "iteration 4: ..."); may be empty.
using ProgressFn = std::function<void(const std::string&)>;

/// \brief Runs the stages in one process.
class StripBlockAdjustment
{
public:
  StripBlockAdjustment();
  ~StripBlockAdjustment();

  void
  setSettings(const StripAdjustmentSettings& settings)
  {
    settings_ = settings;
  }
  const StripAdjustmentSettings&
  getSettings() const
  {
    return settings_;
  }
  /// File coordinates = block coordinates + this (reported origins and matrices).
  void
  setBlockOrigin(const Eigen::Vector3d& origin)
  {
    block_origin_ = origin;
  }
  void
  setProgress(ProgressFn progress)
  {
    progress_ = std::move(progress);
  }

  /// Adjusts the strips. False with a one-line reason when the block cannot be adjusted
  /// (invalid settings, fewer than two strips, no overlap); otherwise the report says how the
  /// adjustment ended (converged, iteration limit, singular).
  bool
  run(const std::vector<Strip>& strips, StripAdjustmentReport& report, std::string& error);

  /// The plan of the last run (overlaps, datum).
  const StripPlan&
  plan() const
  {
    return plan_;
  }
  /// Discrepancy samples of the last run, one per plan overlap (empty for skipped ones).
  const std::vector<OverlapSamples>&
  samples() const
  {
    return samples_;
  }

private:
  StripAdjustmentSettings settings_;
  Eigen::Vector3d block_origin_ = Eigen::Vector3d::Zero();
  ProgressFn progress_;
  StripPlan plan_;
  std::vector<OverlapSamples> samples_;
};

/// Assembles the report from the stages' results: the plan, the final state, the final pass's
/// contributions (with precision cells) and the overlaps' samples (same order as the plan's
/// overlaps; may be empty). Shared by the single-process and the distributed run.
StripAdjustmentReport
makeReport(const StripPlan& plan, const BlockState& state, const std::vector<OverlapContribution>& final_pass,
           const std::vector<OverlapSamples>& samples);

/// The 4 × 4 matrix of a strip's correction in block coordinates (x' = o + t + mR(x − o)).
Eigen::Matrix4d
blockTransformation(const ParameterBlock& block);

}  // namespace strips
}  // namespace pcl_ls3d
