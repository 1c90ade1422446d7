#include <pcl_ls3d/adjustment/iteration_control.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {

bool
converged(const Eigen::VectorXd& dx, const AdjustmentSettings& s)
{
  for (Eigen::Index k = 0; k + 7 <= dx.size(); k += 7) {
    const auto d = dx.segment<7>(k);
    if (!(d.segment<3>(PHI).cwiseAbs().maxCoeff() < s.angle_epsilon &&
          d.head<3>().norm() < s.translation_epsilon && std::abs(d[SCALE]) < s.scale_epsilon))
      return false;
  }
  return true;
}

bool
changesBelow(const GaussMarkovSolution& sol, double fraction)
{
  for (Eigen::Index i = 0; i < sol.dx.size(); ++i)
    if (sol.determinable[static_cast<std::size_t>(i)] &&
        std::abs(sol.dx[i]) > fraction * sol.sigma0 * std::sqrt(sol.qxx(i, i)))
      return false;
  return true;
}

IterationControl::IterationControl(const AdjustmentSettings& settings, std::size_t n, bool culling,
                                   double spacing)
    : settings_(settings), culling_(culling),
      extrapolator_(spacing > 0.0 ? spacing : std::numeric_limits<double>::infinity())
{
  // Coarse phase: every stride-th point only, until the estimate has settled to ~1 σ_i.
  const std::size_t wanted = settings.coarse_observations;
  coarse_stride_ = wanted > 0 && n > 2 * wanted ? (n + wanted - 1) / wanted : 1;
  phase_.coarse = coarse_stride_ > 1;
}

bool
IterationControl::skipMissed(int it) const
{
  return !culling_ && !phase_.frozen && !phase_.coarse && settings_.recheck_interval > 1 &&
         it % settings_.recheck_interval != 0;
}

double
IterationControl::reach(double sigma0, double spacing) const
{
  const double fixed = settings_.max_correspondence_distance;
  if (!isUnlimitedDistance(fixed) || !settings_.automatic_reach || !(sigma0 > 0.0) || !(spacing > 0.0))
    return fixed;
  return std::max(4.0 * spacing, 6.0 * sigma0 + 2.0 * spacing);
}

PhaseStep
advancePhase(IterationPhase& phase, const GaussMarkovSolution& sol, const AdjustmentSettings& s, int it)
{
  PhaseStep step;
  if (phase.coarse) {
    phase.coarse = !(3 * it >= s.max_iterations || changesBelow(sol, 1.0));
    return step;
  }
  // Zuo §4: every angle change below ε (and the translation and scale epsilons).
  if (converged(sol.dx, s)) {
    step.converged = true;
    return step;
  }
  step.afresh = !phase.frozen;
  if (!phase.frozen && (3 * it >= 2 * s.max_iterations || changesBelow(sol, s.freeze_sigma_fraction))) {
    phase.frozen = true;
    step.froze = true;
  }
  return step;
}

IterationControl::Decision
IterationControl::next(const GaussMarkovSolution& sol, const Vector7d& scaling, int it)
{
  const PhaseStep step = advancePhase(phase_, sol, settings_, it);
  Decision d;
  d.converged = step.converged;
  d.freeze = step.froze;
  // While correspondences are searched afresh, extrapolate a creeping iteration (steps
  // compared as displacements at the data's edge).
  if (settings_.accelerate && step.afresh) {
    const Vector7d dx = sol.dx;
    d.extrapolation = extrapolator_.next(dx.cwiseQuotient(scaling), it);
  }
  return d;
}

}  // namespace pcl_ls3d
