#pragma once
/// \file iteration_control.h
/// \brief Stage 5 of the engine: how the iterations are run and when they stop. Coarse-to-fine
///        sampling for big clouds, re-searching missed points only now and then, Besl–McKay
///        extrapolation of creeping steps, freezing the correspondences once the estimate has
///        settled, and Zuo's convergence test (every angle change below ε, §4).

#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/adjustment/gauss_markov.h>
#include <pcl_ls3d/adjustment/step_extrapolation.h>

#include <Eigen/Core>

#include <cstddef>

namespace pcl_ls3d {

/// Zuo's criterion (every angle change below ε) plus translation and scale epsilons, for every
/// block of 7 parameters in \a dx (one for a pair, one per strip for a block).
bool
converged(const Eigen::VectorXd& dx, const AdjustmentSettings& settings);

/// Every estimated parameter changed by less than `fraction` of its formal σ_i.
bool
changesBelow(const GaussMarkovSolution& sol, double fraction);

/// \brief The phase of an adjustment's iterations, a plain value (a distributed strip block
///        keeps it in its state file between iterations).
struct IterationPhase
{
  bool coarse = false;  ///< every k-th point only, until the estimate has settled to ~1 σ_i
  bool frozen = false;  ///< correspondences fixed, converging to the epsilons
};

/// \brief What advancePhase() decided after one solve.
struct PhaseStep
{
  bool converged = false;  ///< stop: the changes fell below the epsilons
  bool froze = false;      ///< the correspondences are frozen from the next iteration on
  bool afresh = false;     ///< this iteration searched its correspondences afresh on all points
};

/// \brief The one iteration policy of the pair engine and the strip block, for any number of
///        parameter blocks: coarse until every change is below 1 σ_i (or a third of the
///        iterations is spent), then converged once the changes are below the epsilons, and
///        frozen once they are below freeze_sigma_fraction σ_i (or after two thirds).
/// \param[in] it the number of solves done, this one included
PhaseStep
advancePhase(IterationPhase& phase, const GaussMarkovSolution& sol, const AdjustmentSettings& settings,
             int it);

/// \brief The state machine of one adjustment's iterations:
///          coarse (every k-th point) → fine (all points, fresh correspondences, extrapolation)
///          → frozen (fixed correspondences) → converged.
class IterationControl
{
public:
  /// \param[in] source_points points the matcher may observe
  /// \param[in] culling the matcher culls points outside the overlap (finite reach)
  /// \param[in] spacing the target's point spacing: steps moving the source's edge by more are
  ///            not creep and are never extrapolated (step_extrapolation.h); 0 or less: no limit
  IterationControl(const AdjustmentSettings& settings, std::size_t source_points, bool culling,
                   double spacing = 0.0);

  /// Observe every k-th point in this iteration (k > 1 only while coarse).
  std::size_t
  stride() const
  {
    return phase_.coarse ? coarse_stride_ : 1;
  }
  /// Whether the matcher culls points outside the overlap (it may start to once the reach is finite).
  void
  setCulling(bool culling)
  {
    culling_ = culling;
  }

  /// Skip points that found no correspondence last time (in all but every recheck-th iteration,
  /// while correspondences are searched afresh and no grid culls the non-overlap).
  bool
  skipMissed(int iteration) const;

  /// The correspondence reach for the next iteration: settings.max_correspondence_distance, or
  /// with settings.automatic_reach and an unlimited distance, max(4 s, 6 σ0 + 2 s) once σ0 of a
  /// previous solve is known (spacing s of the target).
  double
  reach(double sigma0, double spacing) const;

  /// What to do after the solve of iteration `it` (dx already applied).
  struct Decision
  {
    bool converged = false;      ///< stop: the changes fell below the epsilons
    double extrapolation = 0.0;  ///< apply X += extrapolation · dx (Besl & McKay)
    bool freeze = false;         ///< freeze the correspondences from the next iteration on
  };
  /// \param[in] scaling per-parameter scaling to "displacement at the edge of the data"
  Decision
  next(const GaussMarkovSolution& sol, const Vector7d& scaling, int it);

  bool
  frozen() const
  {
    return phase_.frozen;
  }
  bool
  coarse() const
  {
    return phase_.coarse;
  }

private:
  const AdjustmentSettings& settings_;
  std::size_t coarse_stride_ = 1;
  IterationPhase phase_;
  bool culling_ = false;
  StepExtrapolator extrapolator_;
};

}  // namespace pcl_ls3d
