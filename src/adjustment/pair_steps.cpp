// Per-iteration and precision steps of the pair adjustment (declared in matching_steps.h).
#include "matching_steps.h"

#include <pcl_ls3d/adjustment/omitted_parameters.h>
#include <pcl_ls3d/adjustment/spatial_precision.h>
#include <pcl_ls3d/common/parallel.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace pcl_ls3d {
namespace detail {

using Index = Eigen::Index;

NormalEquations
accumulateNormalEquations(const SourceRows& row, const Eigen::VectorXd& weights)
{
  NormalEquations ne;
  const Index m = weights.size();
#pragma omp parallel if (worthParallel(static_cast <std::size_t>(m)))
  {
    NormalEquations local;
#pragma omp for schedule(static) nowait
    for (Index j = 0; j < m; ++j) {
      const std::size_t s = static_cast<std::size_t>(j);
      local.add(row(s), row.set[s].distance, weights[j]);
    }
#pragma omp critical
    ne += local;
  }
  ne.symmetrize();
  return ne;
}

double
meanSquaredGradient(const ObservationSet& set)
{
  double u2 = 0.0;
  for (const Observation& o : set)
    u2 += o.direction.squaredNorm();
  return u2 / static_cast<double>(set.size());
}

IterationRecord
iterationRecord(int it, const NormalEquations& ne, std::size_t m, const GaussMarkovSolution& sol)
{
  IterationRecord rec;
  rec.iteration = it;
  rec.observations_used = ne.n;
  rec.observations_rejected = m - ne.n;
  rec.sigma0 = sol.sigma0;
  rec.max_angle_change = sol.dx.segment<3>(PHI).cwiseAbs().maxCoeff();
  rec.translation_change = sol.dx.head<3>().norm();
  rec.scale_change = std::abs(sol.dx[SCALE]);
  return rec;
}

void
fillCovariance(AdjustmentReport& report, const GaussMarkovSolution& sol, const SourceRows& row,
               const Eigen::VectorXd& weights, const Vector7d& apriori_weights, double cell)
{
  const Matrix7d qxx = sol.qxx;
  report.covariance = sol.sigma0 * sol.sigma0 * qxx;
  report.precision_model = "formal (eq. 14)";
  if (!(sol.redundancy > 0 && cell > 0.0))
    return;
  const Vector7d dx = sol.dx;
  report.covariance = spatialSandwichCovariance(
      row.set.size(), cell, qxx, sol.sigma0, apriori_weights, flags7(sol.determinable),
      [&](std::size_t j, Eigen::Vector3d& x, Vector7d& a, double& p, double& v) {
        p = weights[static_cast<Index>(j)];
        a = row(j).transpose();
        v = row.set[j].distance + a.dot(dx);
        x = row.matcher.position(row.set[j]);
        return true;
      });
  char buf[64];
  std::snprintf(buf, sizeof(buf), "spatial sandwich, cell %.3g", cell);
  report.precision_model = buf;
}

OmittedParameterTest
heldOutScaleTest(const GaussMarkovSolution& sol, const SourceRows& row, const Eigen::VectorXd& weights,
                 const GaussMarkovProblem& problem, double cell)
{
  OmittedParameterTest none;
  const Vector7d pe = problem.apriori_weights;
  if (!std::isinf(pe[SCALE]) || (pe.head<6>().array() == std::numeric_limits<double>::infinity()).any() ||
      !(sol.redundancy > 0) || !(sol.sigma0 > 0.0))
    return none;  // only a rigid fit's held-out scale
  const Vector7d dx = sol.dx;
  // Position, row, weight and residual of observation j at the estimate moved on by `step`.
  const auto observation = [&](const Vector7d& step) {
    return [&, step](std::size_t j, Eigen::Vector3d& x, Vector7d& a, double& p, double& v) {
      p = weights[static_cast<Index>(j)];
      a = row(j).transpose();
      v = row.set[j].distance + a.dot(dx + step);
      x = row.matcher.position(row.set[j]);
      return true;
    };
  };
  // N and AᵀPv at the estimate, plus the a-priori part P_e (X − L_e) of soft parameters.
  Matrix7d N = Matrix7d::Zero(), soft = Matrix7d::Zero();
  Vector7d g = Vector7d::Zero(), a;
  Eigen::Vector3d x;
  double p = 0.0, v = 0.0;
  const auto at_estimate = observation(Vector7d::Zero());
  for (std::size_t j = 0; j < row.set.size(); ++j)
    if (at_estimate(j, x, a, p, v) && p > 0.0) {
      N.noalias() += p * a * a.transpose();
      g.noalias() += (p * v) * a;
    }
  for (int i = 0; i < 7; ++i)
    if (sol.determinable[static_cast<std::size_t>(i)] && pe[i] > 0.0 && std::isfinite(pe[i])) {
      g[i] += pe[i] * (problem.current[i] + dx[i] - problem.apriori_values[i]);
      soft(i, i) = pe[i];
    }
  // The variance behind the report's σ: the sandwich's middle term (for the freed one-step's
  // residuals and leverage), or σ0² (N + P_e).
  std::array<bool, 7> freed = flags7(sol.determinable);
  freed[SCALE] = true;
  const MiddleTermFn middle = [&](const Eigen::VectorXd& step, const Eigen::MatrixXd& q) -> Eigen::MatrixXd {
    if (!(cell > 0.0))
      return sol.sigma0 * sol.sigma0 * (N + soft);
    return spatialMiddleTerm(row.set.size(), cell, Matrix7d(q), sol.sigma0, pe, freed,
                             observation(Vector7d(step)));
  };
  return testOmittedParameters(N, g, Matrix7d(sol.qxx), middle, sol.sigma0, {SCALE});
}

void
storeObservations(AdjustmentReport& report, const GaussMarkovSolution& sol, const SourceRows& row,
                  const Eigen::VectorXd& weights, const std::vector<int>& source_indices)
{
  const std::size_t m = row.set.size();
  const Matrix7d qxx = sol.qxx;
  const Vector7d dx = sol.dx;
  report.observation_source_index.resize(m);
  report.residuals.resize(m);
  report.weights.resize(m);
  report.redundancy_numbers.resize(m);
#pragma omp parallel for schedule(static) if (worthParallel(m))
  for (Index j = 0; j < static_cast<Index>(m); ++j) {
    const std::size_t s = static_cast<std::size_t>(j);
    const RowVector7d a = row(s);
    const int point = row.set[s].point;
    report.observation_source_index[s] =
        source_indices.empty() ? point : source_indices[static_cast<std::size_t>(point)];
    report.residuals[s] = row.set[s].distance + a.dot(dx);
    report.weights[s] = weights[j];
    report.redundancy_numbers[s] = 1.0 - weights[j] * (a * qxx * a.transpose())(0, 0);
  }
}

}  // namespace detail
}  // namespace pcl_ls3d
