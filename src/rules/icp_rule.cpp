#include <pcl_ls3d/rules/icp_rule.h>
#include <pcl_ls3d/rules/local_tin.h>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {

namespace {
// Observations of x' − q along the closest point's error axes: the local normal n (weight 1)
// and two tangents (weight p_t), as (√p u, √p l) so the engine's unit weight applies.
// Each scaled observation has the variance σ_n² of the normal one.
void
addFrameObservations(const Eigen::Vector3d& query, const Eigen::Vector3d& q, const Eigen::Vector3d& n,
                     double tangential_weight, double variance, ConjugateObservations& out)
{
  Eigen::Vector3d e1, e2;
  tin::planeBasis(n, e1, e2);
  const Eigen::Vector3d d = query - q;
  const double s = std::sqrt(tangential_weight);
  out.add(n, n.dot(d), q, variance);
  out.add(s * e1, s * e1.dot(d), q, variance);
  out.add(s * e2, s * e2.dot(d), q, variance);
}

// A spinning scanner's k nearest points often lie on one scan line: their plane (and the noise
// read from its residuals, ~0) is then undefined, and such pairs anchored LS3D-ICP at the
// initial guess on street scans. As the TIN rules do, a line-like set is widened once to
// kWiden·k points; the query is given up when that is a line too. Returns the count (0: none).
int
planeNeighbourhood(const Eigen::Vector3d& query, const TargetSurface& target, int k, double max_distance,
                   std::vector<int>& indices, std::vector<float>& sq_dists, Eigen::Vector3d& normal)
{
  constexpr double kMinSpreadRatio = 0.1;  // λ1/λ2, as the TIN rules (tin_rules.cpp)
  constexpr int kWiden = 3;
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int found = target.nearestKSearch(query, attempt == 0 ? k : kWiden * k, indices, sq_dists);
    if (found < 3 || !(static_cast<double>(sq_dists[0]) <= max_distance * max_distance))
      return 0;
    Eigen::Vector3d eigenvalues;
    if (!tin::neighbourhoodPca(target, indices, found, normal, eigenvalues))
      return 0;
    if (tin::wellSpread(eigenvalues, kMinSpreadRatio))
      return found;
  }
  return 0;
}
}  // namespace

bool
IcpRule::findConjugate(const Eigen::Vector3d& query, const TargetSurface& target, double max_distance,
                       CorrespondenceCache& cache, ConjugateObservations& out) const
{
  if (cache.frozen) {  // keep the last closest point and its error axes (see CorrespondenceCache)
    const int idx = cache.vertices[0];
    if (idx < 0 || idx >= static_cast<int>(target.size()))
      return false;
    const Eigen::Vector3d n(cache.plane[0], cache.plane[1], cache.plane[2]);
    addFrameObservations(query, target.point(idx), n.normalized(), cache.plane[3], cache.variance, out);
    return true;
  }
  thread_local std::vector<int> indices;
  thread_local std::vector<float> sq_dists;
  thread_local std::vector<Eigen::Vector2d> projected;
  cache.vertices[0] = -1;
  Eigen::Vector3d normal;
  const int found =
      planeNeighbourhood(query, target, std::max(3, neighbours_), max_distance, indices, sq_dists, normal);
  if (found < 3)
    return false;
  if (require_enclosure_) {
    // Overlap test: the query must lie inside the local surface, not beyond its border.
    std::array<int, 3> tri;
    tin::projectToPlane(target, indices, found, query, normal, projected);
    if (!tin::enclosingTriangle(projected, tri))
      return false;
  }
  // Error model of the closest point q as a stand-in for the true conjugate point: across the
  // surface the target noise σ_n² (plane-fit residuals of the neighbours); along it an offset
  // anywhere within the neighbourhood, r_k²/4 per axis (uniform disc of radius r_k, the k-th
  // neighbour's distance). Within the closest point's own Voronoi cell the offset would be
  // smaller (1/(2πρ)), but it is re-drawn at every re-association, so it carries no information
  // on the parameters, and at the target's border its mean points inwards by up to r_k: weighted
  // by the cell variance, the tangents pulled the estimate towards the border.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i = 0; i < found; ++i)
    mean += target.point(indices[static_cast<std::size_t>(i)]);
  mean /= found;
  double rss = 0.0;
  for (int i = 0; i < found; ++i) {
    const double h = normal.dot(target.point(indices[static_cast<std::size_t>(i)]) - mean);
    rss += h * h;
  }
  const double rk2 = static_cast<double>(sq_dists[static_cast<std::size_t>(found - 1)]);
  const double var_n = std::max(rss / std::max(1, found - 3), 1e-5 * rk2);
  const double var_t = var_n + 0.25 * rk2;
  const double p_t = var_n / var_t;
  const Eigen::Vector3d q = target.point(indices[0]);
  cache.vertices[0] = indices[0];
  cache.plane = {{static_cast<float>(normal.x()), static_cast<float>(normal.y()),
                  static_cast<float>(normal.z()), static_cast<float>(p_t), 0.f, 0.f}};
  cache.variance = static_cast<float>(var_n);
  addFrameObservations(query, q, normal, p_t, var_n, out);
  return true;
}

}  // namespace pcl_ls3d
