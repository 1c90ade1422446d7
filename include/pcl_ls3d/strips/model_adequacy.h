#pragma once
/// \file model_adequacy.h
/// \brief Is the strips' model large enough? After a rigid block adjustment (-params 6) the
///        scale each strip holds out is tested from the final pass's normal equations
///        (omitted_parameters.h, a score test with the sandwich's variance). Overlaps observe a
///        scale only weakly, through the gradients of the discrepancies along and across track,
///        so σ0 and the discrepancies cannot show it; over 2–5 km strips a scale of 50 ppm still
///        moves a strip's ends by several centimetres. A strip whose freed scale is significant
///        (|z| > held_out_z) and moves its edge by more than held_out_noise_factor × its own noise
///        makes the result NOT CONFIRMED (UNRELIABLE), naming the strips and -params 7.

#include <pcl_ls3d/strips/block_solve.h>
#include <pcl_ls3d/strips/strip_adjustment_report.h>
#include <pcl_ls3d/strips/strip_plan.h>

#include <vector>

namespace pcl_ls3d {
namespace strips {

/// Fills report.held_out and each strip's held_out from the final pass's contributions (with
/// precision cells for the sandwich's variance) and the last solve's state. Needs the
/// report's strips and overlaps (their own noise) filled in. Leaves the verdict alone.
void
testHeldOutParameters(const StripPlan& plan, const BlockState& state,
                      const std::vector<OverlapContribution>& final_pass, StripAdjustmentReport& report);

/// The verdict: a CONVERGED or MAX_ITERATIONS (or already UNRELIABLE) result with flagged
/// strips becomes UNRELIABLE, its message naming the strips, the parameter and -params 7.
void
confirmModel(StripAdjustmentReport& report);

}  // namespace strips
}  // namespace pcl_ls3d
