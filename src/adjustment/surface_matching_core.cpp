#include <pcl_ls3d/adjustment/gauss_markov.h>
#include <pcl_ls3d/adjustment/spatial_precision.h>
#include <pcl_ls3d/adjustment/surface_matching_core.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <unordered_set>

namespace pcl_ls3d {

namespace {

using Index = std::ptrdiff_t;

// Centroid of the source points whose image under the guess falls into the target's bounding
// box (grown by a margin): the reduction origin o_s, near the overlap. False: no overlap.
bool
overlapCentroid(const std::vector<Eigen::Vector3d>& source, const TargetSurface& target,
                const Eigen::Matrix4d& guess, double max_distance, Eigen::Vector3d& centroid,
                Eigen::AlignedBox3d& box, std::vector<int>& inside)
{
  for (std::size_t i = 0; i < target.size(); ++i) {
    const Eigen::Vector3d p = target.point(static_cast<int>(i));
    if (p.allFinite())
      box.extend(p);
  }
  if (box.isEmpty())
    return false;
  const double margin = std::min(max_distance, 0.1 * box.diagonal().norm());
  Eigen::AlignedBox3d grown = box;
  grown.min().array() -= margin;
  grown.max().array() += margin;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  inside.clear();
  for (std::size_t i = 0; i < source.size(); ++i)
    if (grown.contains((guess * source[i].homogeneous()).head<3>())) {
      const Eigen::Vector3d& p = source[i];
      inside.push_back(static_cast<int>(i));
      sum += p;
      ++n;
    }
  if (n == 0)
    return false;
  centroid = sum / static_cast<double>(n);
  return true;
}

bool
converged(const Vector7d& dx, const AdjustmentSettings& s)
{
  return dx.segment<3>(PHI).cwiseAbs().maxCoeff() < s.angle_epsilon &&
         dx.head<3>().norm() < s.translation_epsilon && std::abs(dx[SCALE]) < s.scale_epsilon;
}

AdjustmentReport
failed(AdjustmentReport report, TerminationType type, const std::string& message)
{
  report.termination = type;
  report.message = message;
  return report;
}

}  // namespace

std::vector<int>
thinByVoxel(const std::vector<Eigen::Vector3d>& points, double step)
{
  std::vector<int> kept;
  kept.reserve(step > 0.0 ? points.size() / 4 : points.size());
  if (!(step > 0.0)) {
    for (std::size_t i = 0; i < points.size(); ++i)
      kept.push_back(static_cast<int>(i));
    return kept;
  }
  std::unordered_set<std::uint64_t> seen;
  seen.reserve(points.size() / 2);
  for (std::size_t i = 0; i < points.size(); ++i) {
    // 21 bits per axis (wraps for huge extents, which only merges far-apart voxels rarely).
    std::uint64_t key = 0;
    for (int a = 0; a < 3; ++a)
      key = (key << 21) |
            (static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(points[i][a] / step))) &
             0x1FFFFF);
    if (seen.insert(key).second)
      kept.push_back(static_cast<int>(i));
  }
  return kept;
}

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
  int last_extrapolation = -10;
  Vector7d previous_step = Vector7d::Zero();
  // Coarse phase: every stride-th point only, until the estimate has settled to ~1 σ_i.
  const std::size_t coarse_stride =
      settings.coarse_observations > 0 && n > 2 * settings.coarse_observations
          ? (n + settings.coarse_observations - 1) / settings.coarse_observations
          : 1;
  bool coarse = coarse_stride > 1;
  // Errors in variables (settings.correct_source_noise): σ_s from the source's own roughness,
  // then per observation c = m σ_s² |u|² / var(l), var(l) = m² σ_s² |u|² + σ_t² (target part
  // σ_t² = σ0² − m² σ_s² mean|u|²); the scale column becomes a_m − c l (its correlation with l
  // removed: the adjusted source point x − c l R⁻¹u / m of a Gauss–Helmert linearisation).
  double sigma_s = -1.0;  // < 0: not estimated yet
  double eiv_ms2 = 0.0, eiv_m2s2 = 0.0, eiv_vt = 0.0, mean_u2 = 1.0;
  bool eiv = false;
  auto row = [&](std::size_t s) {
    RowVector7d a = lin.designRow(obs_u_[s], reduced_[static_cast<std::size_t>(obs_point_[s])]);
    if (eiv) {
      const double u2 = obs_u_[s].squaredNorm();
      a[SCALE] -= eiv_ms2 * u2 / (eiv_m2s2 * u2 + eiv_vt) * obs_l_[s];
    }
    return a;
  };
  // Without a finite reach (no overlap grid), points that found no correspondence in their last
  // search are skipped except every recheck_interval-th iteration (and never once frozen).
  missed_.assign(n, 0);
  for (int it = 1; it <= settings.max_iterations; ++it) {
    lin = SimilarityLinearization(SimilarityTransform(X));
    const bool skip_missed = !grid_.built() && !frozen && !coarse && settings.recheck_interval > 1 &&
                             it % settings.recheck_interval != 0;
    eiv = settings.correct_source_noise && sigma_s > 0.0 && sigma0_prev > 0.0;
    if (eiv) {
      eiv_ms2 = X[SCALE] * sigma_s * sigma_s;
      eiv_m2s2 = X[SCALE] * eiv_ms2;
      eiv_vt = std::max(0.0, sigma0_prev * sigma0_prev - eiv_m2s2 * mean_u2);
      eiv = eiv_m2s2 * mean_u2 + eiv_vt > 0.0;
    }

    // 1. Conjugate points of every transformed source point (rule strategy, §2.2).
#pragma omp parallel for schedule(dynamic, 512)
    for (Index i = 0; i < static_cast<Index>(n); ++i) {
      if ((coarse && static_cast<std::size_t>(i) % coarse_stride != 0) ||
          (skip_missed && missed_[static_cast<std::size_t>(i)])) {
        counts_[static_cast<std::size_t>(i)] = 0;
        continue;
      }
      ConjugateObservations out;
      const Eigen::Vector3d q = o_t + lin.apply(reduced_[static_cast<std::size_t>(i)]);
      int c = 0;
      const bool in_reach = grid_.mayOverlap(q);
      if (in_reach && rule.findConjugate(q, target, settings.max_correspondence_distance,
                                         caches_[static_cast<std::size_t>(i)], out))
        for (int k = 0; k < std::min(out.count, stride); ++k) {
          const ConjugateObservation& o = out.items[static_cast<std::size_t>(k)];
          if (!std::isfinite(o.distance) || !o.direction.allFinite())
            continue;
          const std::size_t slot = static_cast<std::size_t>(i) * static_cast<std::size_t>(stride) + static_cast<std::size_t>(c++);
          obs_u_[slot] = o.direction;
          obs_l_[slot] = o.distance;
        }
      counts_[static_cast<std::size_t>(i)] = static_cast<unsigned char>(c);
      missed_[static_cast<std::size_t>(i)] = c == 0;
    }
    // Compact the slots in place (target index never exceeds the slot index).
    m = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < counts_[i]; ++c, ++m) {
        const std::size_t slot = i * static_cast<std::size_t>(stride) + static_cast<std::size_t>(c);
        obs_u_[m] = obs_u_[slot];
        obs_l_[m] = obs_l_[slot];
        obs_point_[m] = static_cast<int>(i);
      }
    report.correspondences = m;
    if (settings.correct_source_noise && sigma_s < 0.0 && m > 0) {
      // Seeds: source points over the target's box (independent of the coarse phase), with
      // ~30 neighbours each.
      const double area = source_box.sizes().head<2>().prod();
      const double density = area > 0.0 ? static_cast<double>(n) / area : 0.0;
      sigma_s = density > 0.0 ? estimateSurfaceNoise(reduced_, inside, std::sqrt(30.0 / (M_PI * density))) : 0.0;
    }
    if (m > 0) {  // mean |u|² (1 for unit directions) for the errors-in-variables term
      double u2 = 0.0;
      for (std::size_t j = 0; j < m; ++j)
        u2 += obs_u_[j].squaredNorm();
      mean_u2 = u2 / static_cast<double>(m);
    }
    if (m == 0 && it == 1)
      return failed(report, TerminationType::NO_OVERLAP,
                    "the rule found no conjugate point on the target (no overlap)");
    if (m < static_cast<std::size_t>(settings.min_observations)) {
      report.iterations = it - 1;
      return failed(report, TerminationType::TOO_FEW_OBSERVATIONS,
                    "only " + std::to_string(m) + " observations (minimum " +
                        std::to_string(settings.min_observations) + ")");
    }

    // 2. Robust weights (eq. 15 by default), optionally with σ_vi from the previous Qxx.
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
    // First iteration: no σ0 yet, so a robust scale (1.4826 · median |l|) stands in for it;
    // without it gross residuals (walls, vegetation) throw the first step far off.
    double sigma0_weights = sigma0_prev;
    if (!(sigma0_weights > 0.0)) {
      std::vector<double> a(obs_l_.begin(), obs_l_.begin() + static_cast<std::ptrdiff_t>(m));
      for (double& x : a)
        x = std::abs(x);
      std::nth_element(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(m / 2), a.end());
      sigma0_weights = 1.4826 * a[m / 2];
    }
    estimator.computeWeights(l, sigma_v_, sigma0_weights, weights_);

    // 3. Normal equations AᵀPA, AᵀPL (eq. 8), one set per thread, then summed.
    NormalEquations ne;
#pragma omp parallel
    {
      NormalEquations local;
#pragma omp for schedule(static) nowait
      for (Index j = 0; j < static_cast<Index>(m); ++j) {
        const std::size_t s = static_cast<std::size_t>(j);
        const double w = std::min(1.0, std::max(0.0, weights_[j]));
        local.add(row(s), obs_l_[s], w);
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
    rec.parameters = X;
    report.log.push_back(rec);
    report.iterations = it;
    report.observations_used = ne.n;
    report.observations_rejected = m - ne.n;
    sigma0_prev = sol.sigma0;

    // 6. Convergence (Zuo §4: angle change below 1e-6 rad); freeze once changes are tiny.
    if (coarse) {  // switch to all points once the changes are below 1 σ_i (or after 1/3)
      const bool settled = 3 * it >= settings.max_iterations;
      int small = 0, estimated = 0;
      for (int i = 0; i < 7; ++i)
        if (sol.determinable[static_cast<std::size_t>(i)]) {
          ++estimated;
          small += std::abs(sol.dx[i]) <= sol.sigma0 * std::sqrt(sol.qxx(i, i));
        }
      coarse = !(settled || small == estimated);
      report.termination = TerminationType::MAX_ITERATIONS;
      continue;
    }
    if (converged(sol.dx, settings)) {
      report.termination = TerminationType::CONVERGED;
      break;
    }
    report.termination = TerminationType::MAX_ITERATIONS;
    // Besl & McKay (1992, §IV-C) acceleration: while correspondences are still searched afresh,
    // a creeping iteration (closest-point rules: consecutive steps nearly parallel, each a fixed
    // fraction ρ of the previous one) is extrapolated to the limit of its geometric series,
    // X += dx ρ/(1 − ρ). Steps are compared as displacements at the data's edge.
    const Vector7d step = sol.dx.cwiseQuotient(problem.scaling);
    if (settings.accelerate && !frozen && it >= last_extrapolation + 3 && previous_step.norm() > 0.0) {
      const double rho = step.norm() / previous_step.norm();
      const double cosine = step.dot(previous_step) / (step.norm() * previous_step.norm());
      if (cosine > 0.98 && rho > 0.3 && rho < 0.97) {
        X += std::min(10.0, rho / (1.0 - rho)) * sol.dx;
        report.log.back().extrapolated = true;
        report.log.back().parameters = X;
        last_extrapolation = it;
      }
    }
    previous_step = step;
    bool negligible = 3 * it >= 2 * settings.max_iterations;
    for (int i = 0; i < 7 && !negligible; ++i)
      if (sol.determinable[static_cast<std::size_t>(i)] &&
          std::abs(sol.dx[i]) > settings.freeze_sigma_fraction * sol.sigma0 * std::sqrt(sol.qxx(i, i)))
        break;
      else if (i == 6)
        negligible = true;
    if (negligible && !frozen) {
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
  report.source_noise = eiv ? sigma_s : 0.0;
  report.covariance = sol.sigma0 * sol.sigma0 * sol.qxx;
  report.precision_model = "formal (eq. 14)";
  if (settings.spatial_precision && sol.redundancy > 0) {
    double cell = settings.precision_cell;
    if (!(cell > 0.0)) {  // 8 × the target's mean XY spacing
      const double area = target_box.sizes().head<2>().prod();
      cell = area > 0.0 ? 8.0 * std::sqrt(area / static_cast<double>(target.size())) : 0.0;
    }
    if (cell > 0.0) {
      SpatialScoreSum scores(cell);
      for (std::size_t j = 0; j < m; ++j) {
        const double w = std::min(1.0, std::max(0.0, weights_[static_cast<Index>(j)]));
        if (!(w > 0.0))
          continue;
        const RowVector7d a = row(j);
        const double v = obs_l_[j] + a.dot(sol.dx);
        scores.add(o_t + lin.apply(reduced_[static_cast<std::size_t>(obs_point_[j])]),
                   a.transpose(), w, (w * v) * a.transpose());
      }
      Matrix7d meat = scores.meat(&sol.qxx);
      for (int i = 0; i < 7; ++i)  // soft a-priori observations: independent, variance σ0²/p_e
        if (sol.determinable[static_cast<std::size_t>(i)] && settings.apriori_weights[i] > 0.0)
          meat(i, i) += sol.sigma0 * sol.sigma0 * settings.apriori_weights[i];
      report.covariance = sol.qxx * meat * sol.qxx;
      char buf[64];
      std::snprintf(buf, sizeof(buf), "spatial sandwich, cell %.3g", cell);
      report.precision_model = buf;
    }
  }
  std::string undetermined;
  for (int i = 0; i < 7; ++i) {
    const std::size_t s = static_cast<std::size_t>(i);
    report.sigmas_formal[i] = sol.sigma0 * std::sqrt(sol.qxx(i, i));
    if (sol.fixed[s])
      report.sigmas[i] = report.sigmas_formal[i] = 0.0;
    else if (!sol.determinable[s]) {
      report.sigmas[i] = report.sigmas_formal[i] = std::numeric_limits<double>::infinity();
      undetermined += (undetermined.empty() ? "" : ", ") + similarityParameterNames()[s];
    }
    else
      report.sigmas[i] = std::sqrt(std::max(0.0, report.covariance(i, i)));
    for (int j = 0; j < 7; ++j) {
      const double d = std::sqrt(report.covariance(i, i) * report.covariance(j, j));
      report.correlation(i, j) = d > 0.0 ? report.covariance(i, j) / d : 0.0;
    }
  }
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

}  // namespace pcl_ls3d
