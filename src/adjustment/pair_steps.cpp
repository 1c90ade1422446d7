// Per-iteration and precision steps of the pair adjustment (declared in matching_steps.h).
#include "matching_steps.h"

#include <pcl_ls3d/adjustment/spatial_precision.h>
#include <pcl_ls3d/common/parallel.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pcl_ls3d {
namespace detail {

using Index = Eigen::Index;

NormalEquations
accumulateNormalEquations(const SourceRows& row, const Eigen::VectorXd& weights)
{
  NormalEquations ne;
  const Index m = weights.size();
#pragma omp parallel if (worthParallel(static_cast<std::size_t>(m)))
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
