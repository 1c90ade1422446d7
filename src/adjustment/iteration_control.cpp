#include <pcl_ls3d/adjustment/iteration_control.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {

bool
converged(const Vector7d& dx, const AdjustmentSettings& s)
{
  return dx.segment<3>(PHI).cwiseAbs().maxCoeff() < s.angle_epsilon &&
         dx.head<3>().norm() < s.translation_epsilon && std::abs(dx[SCALE]) < s.scale_epsilon;
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
: settings_(settings)
, culling_(culling)
, extrapolator_(spacing > 0.0 ? spacing : std::numeric_limits<double>::infinity())
{
  // Coarse phase: every stride-th point only, until the estimate has settled to ~1 σ_i.
  const std::size_t wanted = settings.coarse_observations;
  coarse_stride_ = wanted > 0 && n > 2 * wanted ? (n + wanted - 1) / wanted : 1;
  coarse_ = coarse_stride_ > 1;
}

bool
IterationControl::skipMissed(int it) const
{
  return !culling_ && !frozen_ && !coarse_ && settings_.recheck_interval > 1 &&
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

IterationControl::Decision
IterationControl::next(const GaussMarkovSolution& sol, const Vector7d& scaling, int it)
{
  Decision d;
  const Vector7d dx = sol.dx;
  // Coarse: switch to all points once the changes are below 1 σ_i (or after a third).
  if (coarse_) {
    coarse_ = !(3 * it >= settings_.max_iterations || changesBelow(sol, 1.0));
    return d;
  }
  // Zuo §4: every angle change below ε (and the translation and scale epsilons).
  if (converged(dx, settings_)) {
    d.converged = true;
    return d;
  }
  // While correspondences are searched afresh, extrapolate a creeping iteration (steps
  // compared as displacements at the data's edge).
  if (settings_.accelerate && !frozen_)
    d.extrapolation = extrapolator_.next(dx.cwiseQuotient(scaling), it);
  // Freeze once the changes are tiny (or after two thirds of the iterations).
  if (!frozen_ && (3 * it >= 2 * settings_.max_iterations ||
                   changesBelow(sol, settings_.freeze_sigma_fraction))) {
    frozen_ = true;
    d.freeze = true;
  }
  return d;
}

}  // namespace pcl_ls3d
