#pragma once
/// \file block_solve.h
/// \brief Stage "solve" of the strip adjustment: sums the overlaps' contributions into the
///        engine's BlockNormalEquations, solves all strips at once (solveGaussMarkov with the
///        a-priori observations of the datum and the model, rank test per parameter), updates
///        the parameters and decides how to go on — the engine's IterationControl phases
///        (coarse → all points → frozen correspondences → converged, Zuo §4) for a block. The
///        whole state between iterations is this plain struct, so a distributed run can write
///        it to a file and a single process can keep it in memory with the same result.

#include <pcl_ls3d/adjustment/adjustment_report.h>
#include <pcl_ls3d/strips/overlap_contribution.h>
#include <pcl_ls3d/strips/strip_plan.h>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace strips {

/// \brief One line of the block's iteration log.
struct BlockIterationRecord
{
  int iteration = 0;
  std::size_t observations = 0, used = 0;
  double sigma0 = 0.0;
  double max_angle_change = 0.0;        ///< [rad] over all strips
  double max_translation_change = 0.0;  ///< [length] over all strips
  double max_scale_change = 0.0;
  bool coarse = false, frozen = false;  ///< phase the iteration's matches ran in
};

/// \brief Where the adjustment stands between two stages.
struct BlockState
{
  enum class Phase
  {
    ITERATE,
    EVALUATE,
    DONE
  };
  Phase phase = Phase::ITERATE;
  int iteration = 0;                      ///< solves done
  std::vector<Vector7d> values;           ///< per strip (tx, ty, tz, φ, ω, κ, m)
  double sigma0 = 0.0;                    ///< of the last solve
  double soft_sigma_obs = 0.0;            ///< σ_obs of the soft datum (fixed at iteration 1)
  Eigen::MatrixXd qxx;                    ///< 7N × 7N of the last solve
  std::vector<bool> fixed, determinable;  ///< 7N flags of the last solve
  long redundancy = 0;
  std::size_t observations = 0;  ///< with weight > 0 in the last solve
  bool coarse = true, frozen = false;
  TerminationType termination = TerminationType::NOT_RUN;
  std::string message;
  std::vector<BlockIterationRecord> log;

  /// The parameter blocks at these values.
  std::vector<ParameterBlock>
  blocks(const StripPlan& plan) const;
};

/// The state before the first iteration (identity for every strip).
BlockState
initialState(const StripPlan& plan);

/// What a match job needs for overlap (i, j) in the next pass.
MatchInput
matchInput(const StripPlan& plan, const BlockState& state, int i, int j);

/// One solve from the contributions of all used overlaps (any order): updates the state and
/// sets its phase (EVALUATE once converged or out of iterations, DONE on failure).
void
solveIteration(const StripPlan& plan, const std::vector<OverlapContribution>& contributions,
               BlockState& state);

}  // namespace strips
}  // namespace pcl_ls3d
