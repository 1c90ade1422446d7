// Stage 5 (iteration_control.h): coarse → fine → frozen → converged, Besl–McKay extrapolation of
// a creeping step sequence, and when missed points are searched again.
#include <pcl_ls3d/adjustment/iteration_control.h>

#include <gtest/gtest.h>

using namespace pcl_ls3d;

namespace {

// A solve whose every parameter has σ_i = 1 and the given change.
GaussMarkovSolution
step(const Vector7d& dx)
{
  GaussMarkovSolution s;
  s.ok = true;
  s.dx = dx;
  s.qxx = Eigen::MatrixXd::Identity(7, 7);
  s.sigma0 = 1.0;
  s.fixed.assign(7, false);
  s.determinable.assign(7, true);
  return s;
}

TEST(IterationControl, CoarseThenFineThenFrozenThenConverged)
{
  AdjustmentSettings settings;
  settings.coarse_observations = 100;
  settings.max_iterations = 30;
  IterationControl control(settings, 1000, true);
  EXPECT_TRUE(control.coarse());
  EXPECT_EQ(control.stride(), 10u);
  const Vector7d ones = Vector7d::Ones();
  control.next(step(5.0 * ones), ones, 1);  // above 1 σ: stays coarse
  EXPECT_EQ(control.stride(), 10u);
  control.next(step(0.5 * ones), ones, 2);  // below 1 σ: all points from now on
  EXPECT_EQ(control.stride(), 1u);
  IterationControl::Decision d = control.next(step(0.5 * ones), ones, 3);
  EXPECT_FALSE(d.freeze);
  EXPECT_FALSE(d.converged);
  d = control.next(step(0.05 * ones), ones, 4);  // below freeze_sigma_fraction = 0.1
  EXPECT_TRUE(d.freeze);
  EXPECT_TRUE(control.frozen());
  d = control.next(step(1e-9 * ones), ones, 5);
  EXPECT_TRUE(d.converged);
  EXPECT_FALSE(d.freeze);  // frozen once only
}

TEST(IterationControl, SmallCloudsStartFineAndFreezeAfterTwoThirds)
{
  AdjustmentSettings settings;
  settings.max_iterations = 9;
  IterationControl control(settings, 1000, false);
  EXPECT_FALSE(control.coarse());
  const Vector7d ones = Vector7d::Ones();
  for (int it = 1; it < 6; ++it)
    EXPECT_FALSE(control.next(step(3.0 * ones), ones, it).freeze);
  EXPECT_TRUE(control.next(step(3.0 * ones), ones, 6).freeze);  // 3 · 6 ≥ 2 · 9
}

TEST(IterationControl, CreepingStepsAreExtrapolated)
{
  AdjustmentSettings settings;
  settings.freeze_sigma_fraction = 0.0;  // never freeze on the changes
  settings.max_iterations = 100;
  IterationControl control(settings, 1000, false);
  const Vector7d ones = Vector7d::Ones();
  Vector7d dx = Vector7d::Ones();
  double factor = 0.0;
  for (int it = 1; it <= 4 && factor == 0.0; ++it, dx *= 0.8)
    factor = control.next(step(dx), ones, it).extrapolation;
  EXPECT_NEAR(factor, 0.8 / (1.0 - 0.8), 1e-12);  // the limit of the geometric series
}

TEST(IterationControl, MissedPointsAreSearchedAgainEveryRecheckInterval)
{
  AdjustmentSettings settings;
  settings.recheck_interval = 3;
  const IterationControl no_grid(settings, 1000, false);
  EXPECT_TRUE(no_grid.skipMissed(1));
  EXPECT_TRUE(no_grid.skipMissed(2));
  EXPECT_FALSE(no_grid.skipMissed(3));
  const IterationControl culling(settings, 1000, true);  // the grid already skips them
  EXPECT_FALSE(culling.skipMissed(1));
}

// The policy for N parameter blocks (the strip block): converged only when every block's
// changes are below the epsilons; the phase is a plain value the caller keeps.
TEST(IterationControl, AdvancePhaseJudgesEveryBlock)
{
  AdjustmentSettings settings;
  settings.max_iterations = 30;
  Eigen::VectorXd dx = Eigen::VectorXd::Constant(14, 1e-9);
  EXPECT_TRUE(converged(dx, settings));
  dx[7 + 2] = 2.0 * settings.translation_epsilon;  // the second block's tz
  EXPECT_FALSE(converged(dx, settings));

  GaussMarkovSolution sol;
  sol.ok = true;
  sol.sigma0 = 1.0;
  sol.qxx = Eigen::MatrixXd::Identity(14, 14);
  sol.determinable.assign(14, true);
  sol.fixed.assign(14, false);
  sol.dx = Eigen::VectorXd::Constant(14, 0.5);  // below 1 σ: the coarse phase ends
  IterationPhase phase{true, false};
  PhaseStep s = advancePhase(phase, sol, settings, 1);
  EXPECT_FALSE(phase.coarse);
  EXPECT_FALSE(s.converged || s.froze || s.afresh);
  sol.dx = Eigen::VectorXd::Constant(14, 0.05);  // below freeze_sigma_fraction σ
  s = advancePhase(phase, sol, settings, 2);
  EXPECT_TRUE(s.froze && s.afresh && phase.frozen);
  sol.dx = dx;  // one block still above its ε
  s = advancePhase(phase, sol, settings, 3);
  EXPECT_FALSE(s.converged || s.froze || s.afresh);
  sol.dx.setConstant(1e-9);
  EXPECT_TRUE(advancePhase(phase, sol, settings, 4).converged);
}

}  // namespace
