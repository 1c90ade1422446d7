#include <pcl_ls3d/adjustment/surface_noise.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace pcl_ls3d {

namespace {

std::uint64_t
cellKey(const Eigen::Array3i& c)
{
  constexpr std::int64_t mask = (std::int64_t(1) << 21) - 1;
  return (static_cast<std::uint64_t>(c.x() & mask) << 42) | (static_cast<std::uint64_t>(c.y() & mask) << 21) |
         static_cast<std::uint64_t>(c.z() & mask);
}

Eigen::Array3i
cellOf(const Eigen::Vector3d& x, double inv_cell)
{
  return (x * inv_cell).array().floor().cast<int>();
}

// Median of the per-neighbourhood σ̂² ~ σ² χ²_ν/ν of local quadrics, corrected to a mean.
class NoisePool
{
public:
  // Quadric w(u, v) in the PCA frame of the neighbourhood (u, v scaled by inv_scale).
  void
  add(const std::vector<Eigen::Vector3d>& hood, double inv_scale)
  {
    const int k = static_cast<int>(hood.size());
    if (k < 12)
      return;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : hood)
      mean += p;
    mean /= k;
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : hood)
      cov.noalias() += (p - mean) * (p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
    es.computeDirect(cov);
    const Eigen::Vector3d n = es.eigenvectors().col(0), e1 = es.eigenvectors().col(2),
                          e2 = es.eigenvectors().col(1);
    Eigen::Matrix<double, 6, 6> N = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
    double ww = 0.0;
    for (const auto& p : hood) {
      const Eigen::Vector3d d = p - mean;
      const double u = d.dot(e1) * inv_scale, v = d.dot(e2) * inv_scale, w = d.dot(n);
      Eigen::Matrix<double, 6, 1> a;
      a << 1, u, v, u * u, u * v, v * v;
      N.noalias() += a * a.transpose();
      b.noalias() += a * w;
      ww += w * w;
    }
    Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(N);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-9 * ldlt.vectorD().maxCoeff()))
      return;
    const Eigen::Matrix<double, 6, 1> x = ldlt.solve(b);
    variances_.push_back(std::max(0.0, ww - x.dot(b)) / (k - 6));
    dof_ += k - 6;
  }

  // Median of σ̂² is ≈ σ² (1 − 2/(9ν))³ (Wilson–Hilferty); 0 without neighbourhoods.
  double
  sigma()
  {
    if (variances_.empty())
      return 0.0;
    const double nu = dof_ / static_cast<double>(variances_.size());
    auto mid = variances_.begin() + static_cast<std::ptrdiff_t>(variances_.size() / 2);
    std::nth_element(variances_.begin(), mid, variances_.end());
    const double c = 1.0 - 2.0 / (9.0 * nu);
    return std::sqrt(*mid / (c * c * c));
  }

private:
  std::vector<double> variances_;
  double dof_ = 0.0;
};

}  // namespace

double
estimateSurfaceNoise(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& seeds, double radius,
                     std::size_t max_seeds)
{
  if (!(radius > 0.0) || seeds.empty() || points.empty())
    return 0.0;
  // Spread the seeds over the given list; hash them by cells of edge `radius`.
  const std::size_t step = std::max<std::size_t>(1, seeds.size() / max_seeds);
  std::vector<int> chosen;
  for (std::size_t i = 0; i < seeds.size() && chosen.size() < max_seeds; i += step)
    chosen.push_back(seeds[i]);
  const double inv = 1.0 / radius;
  std::unordered_map<std::uint64_t, std::vector<int>> seed_cells;  // cell -> seed slots
  for (std::size_t s = 0; s < chosen.size(); ++s) {
    const Eigen::Array3i c = cellOf(points[static_cast<std::size_t>(chosen[s])], inv);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          seed_cells[cellKey(c + Eigen::Array3i(dx, dy, dz))].push_back(static_cast<int>(s));
  }
  // One pass over all points: collect the neighbours of every seed.
  std::vector<std::vector<Eigen::Vector3d>> hoods(chosen.size());
  const double r2 = radius * radius;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Array3i c = cellOf(p, inv);
    const auto it = seed_cells.find(cellKey(c));
    if (it == seed_cells.end())
      continue;
    for (int s : it->second)
      if ((p - points[static_cast<std::size_t>(chosen[static_cast<std::size_t>(s)])]).squaredNorm() <= r2)
        hoods[static_cast<std::size_t>(s)].push_back(p);
  }
  // Local quadric w(u, v) in the PCA frame of each neighbourhood; σ² = RSS / (k − 6).
  NoisePool pool;
  for (const auto& hood : hoods)
    pool.add(hood, inv);
  return pool.sigma();
}

double
estimateSurfaceNoise(const TargetSurface& surface, const std::vector<Eigen::Vector3d>& seeds, int k,
                     std::size_t max_seeds)
{
  if (seeds.empty() || surface.size() < static_cast<std::size_t>(k))
    return 0.0;
  const std::size_t step = std::max<std::size_t>(1, seeds.size() / max_seeds);
  NoisePool pool;
  std::vector<int> indices;
  std::vector<float> sq_dists;
  std::vector<Eigen::Vector3d> hood;
  for (std::size_t i = 0; i < seeds.size(); i += step) {
    const int found = surface.nearestKSearch(seeds[i], k, indices, sq_dists);
    if (found < 12)
      continue;
    hood.clear();
    for (int j = 0; j < found; ++j)
      hood.push_back(surface.point(indices[static_cast<std::size_t>(j)]));
    const double r2 = static_cast<double>(sq_dists[static_cast<std::size_t>(found - 1)]);
    pool.add(hood, r2 > 0.0 ? 1.0 / std::sqrt(r2) : 1.0);
  }
  return pool.sigma();
}

double
estimatePointSpacing(const TargetSurface& surface, std::size_t samples)
{
  const std::size_t n = surface.size();
  if (n < 2)
    return 0.0;
  const std::size_t step = std::max<std::size_t>(1, n / samples);
  std::vector<double> nearest;
  std::vector<int> indices;
  std::vector<float> sq_dists;
  for (std::size_t i = 0; i < n; i += step) {
    const Eigen::Vector3d p = surface.point(static_cast<int>(i));
    const int found = surface.nearestKSearch(p, 2, indices, sq_dists);
    for (int j = 0; j < found; ++j)  // the first neighbour at distance 0 is the point itself
      if (indices[static_cast<std::size_t>(j)] != static_cast<int>(i) &&
          sq_dists[static_cast<std::size_t>(j)] > 0.f) {
        nearest.push_back(std::sqrt(static_cast<double>(sq_dists[static_cast<std::size_t>(j)])));
        break;
      }
  }
  if (nearest.empty())
    return 0.0;
  auto mid = nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2);
  std::nth_element(nearest.begin(), mid, nearest.end());
  return *mid;
}

}  // namespace pcl_ls3d
