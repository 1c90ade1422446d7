#include <pcl_ls3d/adjustment/errors_in_variables.h>
#include <pcl_ls3d/adjustment/gauss_markov.h>
#include <pcl_ls3d/adjustment/step_extrapolation.h>
#include <pcl_ls3d/adjustment/spatial_precision.h>
#include <pcl_ls3d/adjustment/surface_matching_core.h>

#include "matching_steps.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

namespace pcl_ls3d {

namespace {

using Index = std::ptrdiff_t;
using namespace detail;

AdjustmentReport
failed(AdjustmentReport report, TerminationType type, const std::string& message)
{
  report.termination = type;
  report.message = message;
  return report;
}

}  // namespace

AdjustmentReport
SurfaceMatchingCore::run(const std::vector<Eigen::Vector3d>& source,
                         const std::vector<int>& source_indices,
                         const TargetSurface& target,
                         const ConjugateRule& rule,
                         const RobustEstimator& estimator,
                         const AdjustmentSettings& settings,
                         const Eigen::Matrix4d& guess)
{
  AdjustmentReport report;
  report.rule_name = rule.name();
  report.estimator_name = estimator.name();
  report.source_points = source.size();
  std::string why;
  if (!settings.isValid(&why))
    return failed(report, TerminationType::INVALID_INPUT, "invalid settings: " + why);
  if (source.empty())
    return failed(report, TerminationType::INVALID_INPUT, "no valid (finite) source points");
  if (target.size() < 3)
    return failed(report, TerminationType::INVALID_INPUT, "fewer than 3 valid target points");
  if (!guess.allFinite())
    return failed(report, TerminationType::INVALID_INPUT, "initial guess is not finite");

  // Reduction to a local origin near the overlap (DESIGN: conditioning on georeferenced data).
  Eigen::Vector3d o_s;
  Eigen::AlignedBox3d target_box;
  std::vector<int> inside;  // source points over the target's box: seeds for σ_s
  if (!overlapCentroid(source, target, guess, settings.max_correspondence_distance, o_s, target_box, inside))
    return failed(report, TerminationType::NO_OVERLAP,
                  "no source point falls over the target's extent under the initial guess");
  const Eigen::Vector3d o_t = (guess * o_s.homogeneous()).head<3>();
  report.local_origin_source = o_s;
  report.local_origin_target = o_t;

  // Initial estimate and a-priori values (eq. 9); fixed parameters start exactly at L_e.
  Vector7d X = SimilarityTransform::fromMatrix(globalToLocal(guess, o_s, o_t)).vector();
  X.head<3>().setZero();  // o_t = guess(o_s) by construction
  const Vector7d apriori = settings.apriori_from_guess ? X : settings.apriori_values;
  for (int i = 0; i < 7; ++i)
    if (settings.isFixed(i))
      X[i] = apriori[i];

  const std::size_t n = source.size();
  reduced_.resize(n);
  double radius = 0.0;
  Eigen::AlignedBox3d source_box;
  for (std::size_t i = 0; i < n; ++i) {
    reduced_[i] = source[i] - o_s;
    radius = std::max(radius, reduced_[i].norm());
    source_box.extend(reduced_[i]);
  }
  caches_.assign(n, CorrespondenceCache());
  // Overlap culling: with a finite maximum correspondence distance, points with no target point
  // within it cannot correspond (rule contract), so their neighbour search is skipped.
  grid_.build(target, settings.max_correspondence_distance);
  const std::size_t slots = n * static_cast<std::size_t>(std::max(1, std::min(3, rule.maxObservations())));
  counts_.resize(n);
  if (obs_u_.size() < slots) {
    obs_u_.resize(slots);
    obs_l_.resize(slots);
    obs_point_.resize(slots);
  }
  const int stride = static_cast<int>(slots / n);

  GaussMarkovProblem problem;
  problem.apriori_values = apriori;
  problem.apriori_weights = settings.apriori_weights;
  problem.determinability_threshold = settings.determinability_threshold;
  // Unit change of each scaled parameter displaces the edge of the data by about one unit.
  const double inv_r = radius > 0.0 ? 1.0 / radius : 1.0;
  problem.scaling << 1, 1, 1, inv_r, inv_r, inv_r, inv_r;

  GaussMarkovSolution sol;
  SimilarityLinearization lin{SimilarityTransform(X)};
  double sigma0_prev = 0.0;
  std::size_t m = 0;
  bool frozen = false;
  StepExtrapolator extrapolator;
  // Coarse phase: every stride-th point only, until the estimate has settled to ~1 σ_i.
  const std::size_t coarse_stride =
      settings.coarse_observations > 0 && n > 2 * settings.coarse_observations
          ? (n + settings.coarse_observations - 1) / settings.coarse_observations
          : 1;
  bool coarse = coarse_stride > 1;
  // Errors in variables (errors_in_variables.h): σ_s from the source's own roughness around
  // the points over the target (independent of the coarse phase), ~30 neighbours each.
  ScaleColumnCorrection eiv;
  if (settings.correct_source_noise) {
    const double area = source_box.sizes().head<2>().prod();
    const double density = area > 0.0 ? static_cast<double>(n) / area : 0.0;
    if (density > 0.0)
      eiv.setSourceNoise(estimateSurfaceNoise(reduced_, inside, std::sqrt(30.0 / (M_PI * density))));
  }
  auto row = [&](std::size_t s) {
    RowVector7d a = lin.designRow(obs_u_[s], reduced_[static_cast<std::size_t>(obs_point_[s])]);
    a[SCALE] -= eiv.coefficient(obs_u_[s].squaredNorm()) * obs_l_[s];
    return a;
  };
  missed_.assign(n, 0);
  for (int it = 1; it <= settings.max_iterations; ++it) {
    lin = SimilarityLinearization(SimilarityTransform(X));

    // 1. Conjugate points of every (selected) transformed source point (rule strategy, §2.2).
    //    Without a finite reach (no overlap grid) points that found no correspondence are
    //    searched again only every recheck_interval-th iteration.
    const bool skip_missed = !grid_.built() && !frozen && !coarse && settings.recheck_interval > 1 &&
                             it % settings.recheck_interval != 0;
    m = findCorrespondences(lin, o_t, target, rule, settings.max_correspondence_distance,
                            coarse ? coarse_stride : 1, skip_missed, stride);
    report.correspondences = m;
    if (m == 0 && it == 1)
      return failed(report, TerminationType::NO_OVERLAP,
                    "the rule found no conjugate point on the target (no overlap)");
    if (m < static_cast<std::size_t>(settings.min_observations)) {
      report.iterations = it - 1;
      return failed(report, TerminationType::TOO_FEW_OBSERVATIONS,
                    "only " + std::to_string(m) + " observations (minimum " +
                        std::to_string(settings.min_observations) + ")");
    }
    double u2 = 0.0;  // mean |u|² (1 for unit directions) for the errors-in-variables term
    for (std::size_t j = 0; j < m; ++j)
      u2 += obs_u_[j].squaredNorm();
    eiv.update(X[SCALE], sigma0_prev, u2 / static_cast<double>(m));

    // 2. Robust weights (eq. 15 by default), optionally with σ_vi from the previous Qxx. The
    //    first iteration has no σ0: a robust scale stands in, or gross residuals (walls,
    //    vegetation) would throw the first step far off.
    const Eigen::Map<const Eigen::VectorXd> l(obs_l_.data(), static_cast<Index>(m));
    weights_.resize(static_cast<Index>(m));
    sigma_v_.resize(0);
    if (estimator.needsResidualSigmas() && sigma0_prev > 0.0) {
      sigma_v_.resize(static_cast<Index>(m));
#pragma omp parallel for schedule(static)
      for (Index j = 0; j < static_cast<Index>(m); ++j) {
        const RowVector7d a = row(static_cast<std::size_t>(j));
        sigma_v_[j] = sigma0_prev * std::sqrt(std::max(0.0, 1.0 - a * sol.qxx * a.transpose()));
      }
    }
    estimator.computeWeights(l, sigma_v_, sigma0_prev > 0.0 ? sigma0_prev : robustScale(obs_l_, m),
                             weights_);

    // 3. Normal equations AᵀPA, AᵀPL (eq. 8), one set per thread, then summed.
    NormalEquations ne;
#pragma omp parallel
    {
      NormalEquations local;
#pragma omp for schedule(static) nowait
      for (Index j = 0; j < static_cast<Index>(m); ++j) {
        const std::size_t s = static_cast<std::size_t>(j);
        local.add(row(s), obs_l_[s], std::min(1.0, std::max(0.0, weights_[j])));
      }
#pragma omp critical
      ne += local;
    }
    ne.symmetrize();
    if (ne.n < static_cast<std::size_t>(settings.min_observations)) {
      report.iterations = it - 1;
      return failed(report, TerminationType::TOO_FEW_OBSERVATIONS,
                    "only " + std::to_string(ne.n) + " observations kept after robust weighting");
    }

    // 4. Gauss–Markoff solve with a-priori observations (eqs. 9–11).
    problem.current = X;
    sol = solveGaussMarkov(ne, problem);
    if (!sol.ok) {
      report.iterations = it;
      return failed(report, TerminationType::SINGULAR, sol.message);
    }
    if (sol.redundancy <= 0) {
      report.iterations = it;
      return failed(report, TerminationType::TOO_FEW_OBSERVATIONS, "no redundancy (r = n - u <= 0)");
    }

    // 5. Update and log.
    X += sol.dx;
    if (!X.allFinite() || !(X[SCALE] > 0.0)) {
      report.iterations = it;
      return failed(report, TerminationType::DIVERGED, "the estimate became non-finite or m <= 0");
    }
    IterationRecord rec;
    rec.iteration = it;
    rec.observations_used = ne.n;
    rec.observations_rejected = m - ne.n;
    rec.sigma0 = sol.sigma0;
    rec.max_angle_change = sol.dx.segment<3>(PHI).cwiseAbs().maxCoeff();
    rec.translation_change = sol.dx.head<3>().norm();
    rec.scale_change = std::abs(sol.dx[SCALE]);
    report.iterations = it;
    report.observations_used = ne.n;
    report.observations_rejected = m - ne.n;
    report.termination = TerminationType::MAX_ITERATIONS;
    sigma0_prev = sol.sigma0;

    // 6. Coarse phase: switch to all points once the changes are below 1 σ_i (or after 1/3).
    if (coarse) {
      coarse = !(3 * it >= settings.max_iterations || changesBelow(sol, 1.0));
      rec.parameters = X;
      report.log.push_back(rec);
      continue;
    }
    // 7. Convergence (Zuo §4: angle change below 1e-6 rad).
    if (converged(sol.dx, settings)) {
      rec.parameters = X;
      report.log.push_back(rec);
      report.termination = TerminationType::CONVERGED;
      break;
    }
    // 8. While correspondences are searched afresh, extrapolate a creeping iteration
    //    (step_extrapolation.h; steps compared as displacements at the data's edge); freeze the
    //    correspondences once the changes are tiny (or after 2/3 of the iterations).
    if (settings.accelerate && !frozen) {
      const double factor = extrapolator.next(sol.dx.cwiseQuotient(problem.scaling), it);
      X += factor * sol.dx;
      rec.extrapolated = factor > 0.0;
    }
    rec.parameters = X;
    report.log.push_back(rec);
    if (!frozen && (3 * it >= 2 * settings.max_iterations ||
                    changesBelow(sol, settings.freeze_sigma_fraction))) {
      frozen = true;
      for (CorrespondenceCache& c : caches_)
        c.frozen = true;
    }
  }

  // Precision: formal σ0² Qxx (eq. 14) and the spatial sandwich (spatial_precision.h).
  report.parameters = X;
  report.transformation = localToGlobal(SimilarityTransform(X).matrix(), o_s, o_t);
  report.sigma0 = sol.sigma0;
  report.qxx = sol.qxx;
  report.fixed = sol.fixed;
  report.determinable = sol.determinable;
  report.redundancy = sol.redundancy;
  report.source_noise = eiv.active() ? eiv.sourceNoise() : 0.0;
  report.covariance = sol.sigma0 * sol.sigma0 * sol.qxx;
  report.precision_model = "formal (eq. 14)";
  double cell = settings.precision_cell;
  if (!(cell > 0.0)) {  // 8 × the target's mean XY spacing
    const double area = target_box.sizes().head<2>().prod();
    cell = area > 0.0 ? 8.0 * std::sqrt(area / static_cast<double>(target.size())) : 0.0;
  }
  if (settings.spatial_precision && sol.redundancy > 0 && cell > 0.0) {
    report.covariance = spatialSandwichCovariance(
        m, cell, sol.qxx, sol.sigma0, settings.apriori_weights, sol.determinable,
        [&](std::size_t j, Eigen::Vector3d& x, Vector7d& a, double& p, double& v) {
          p = std::min(1.0, std::max(0.0, weights_[static_cast<Index>(j)]));
          a = row(j).transpose();
          v = obs_l_[j] + a.dot(sol.dx);
          x = o_t + lin.apply(reduced_[static_cast<std::size_t>(obs_point_[j])]);
          return true;
        });
    char buf[64];
    std::snprintf(buf, sizeof(buf), "spatial sandwich, cell %.3g", cell);
    report.precision_model = buf;
  }
  const std::string undetermined = fillPrecision(report, sol);
  if (!undetermined.empty())
    report.message = "undeterminable from this geometry (held at their initial values): " + undetermined;
  if (report.termination == TerminationType::MAX_ITERATIONS)
    report.message += std::string(report.message.empty() ? "" : "; ") +
                      "iteration limit reached before the changes fell below the epsilons";

  // Reliability: residuals (eq. 12) and redundancy numbers r_i = 1 − p_i a_iᵀ Qxx a_i.
  if (settings.store_observations) {
    report.observation_source_index.resize(m);
    report.residuals.resize(m);
    report.weights.resize(m);
    report.redundancy_numbers.resize(m);
#pragma omp parallel for schedule(static)
    for (Index j = 0; j < static_cast<Index>(m); ++j) {
      const std::size_t s = static_cast<std::size_t>(j);
      const RowVector7d a = row(s);
      const double w = std::min(1.0, std::max(0.0, weights_[j]));
      report.observation_source_index[s] = source_indices.empty() ? obs_point_[s] : source_indices[static_cast<std::size_t>(obs_point_[s])];
      report.residuals[s] = obs_l_[s] + a.dot(sol.dx);
      report.weights[s] = w;
      report.redundancy_numbers[s] = 1.0 - w * (a * sol.qxx * a.transpose())(0, 0);
    }
  }
  return report;
}

std::size_t
SurfaceMatchingCore::findCorrespondences(const SimilarityLinearization& lin,
                                         const Eigen::Vector3d& o_t, const TargetSurface& target,
                                         const ConjugateRule& rule, double max_distance,
                                         std::size_t every, bool skip_missed, int stride)
{
  const std::size_t n = reduced_.size();
#pragma omp parallel for schedule(dynamic, 512)
  for (Index i = 0; i < static_cast<Index>(n); ++i) {
    const std::size_t p = static_cast<std::size_t>(i);
    counts_[p] = 0;
    if (p % every != 0 || (skip_missed && missed_[p]))
      continue;
    const Eigen::Vector3d q = o_t + lin.apply(reduced_[p]);
    ConjugateObservations out;
    int c = 0;
    if (grid_.mayOverlap(q) && rule.findConjugate(q, target, max_distance, caches_[p], out))
      for (int k = 0; k < std::min(out.count, stride); ++k) {
        const ConjugateObservation& o = out.items[static_cast<std::size_t>(k)];
        if (!std::isfinite(o.distance) || !o.direction.allFinite())
          continue;
        const std::size_t slot = p * static_cast<std::size_t>(stride) + static_cast<std::size_t>(c++);
        obs_u_[slot] = o.direction;
        obs_l_[slot] = o.distance;
      }
    counts_[p] = static_cast<unsigned char>(c);
    missed_[p] = c == 0;
  }
  // Compact the slots in place (target index never exceeds the slot index).
  std::size_t m = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < counts_[i]; ++c, ++m) {
      const std::size_t slot = i * static_cast<std::size_t>(stride) + static_cast<std::size_t>(c);
      obs_u_[m] = obs_u_[slot];
      obs_l_[m] = obs_l_[slot];
      obs_point_[m] = static_cast<int>(i);
    }
  return m;
}

}  // namespace pcl_ls3d
