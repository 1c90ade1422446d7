/// \file dimensionality_features.cpp
/// \brief Optimal neighbourhood (minimal eigen-entropy) and dimensionality features.

#include <pcl_ls3d/segmentation/dimensionality_features.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace segmentation {
namespace {

/// Covariance (1/k normalisation) of the first k neighbours from running moments.
Eigen::Matrix3d
covarianceFromMoments(const Eigen::Vector3d& sum, const Eigen::Matrix3d& sum_sq, int k)
{
  const Eigen::Vector3d mean = sum / k;
  return sum_sq / k - mean * mean.transpose();
}

/// Eigen-entropy E = −Σ e ln e, e_i = λ_i / Σλ (Weinmann et al.); +inf for zero extent.
double
eigenEntropy(const Eigen::Vector3d& lambda)
{
  const double total = lambda.sum();
  if (!(total > 0.0))
    return std::numeric_limits<double>::infinity();
  double e = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double p = lambda[i] / total;
    if (p > 0.0)
      e -= p * std::log(p);
  }
  return e;
}

Eigen::Vector3d
clampedEigenvalues(const Eigen::Vector3d& ascending)
{
  return ascending.cwiseMax(0.0);
}

/// The tested neighbourhood size of least eigenentropy (sizes k_min, k_min + step, ... ≤
/// min(k_max, n); only n itself if n < k_min): its covariance, size and entropy.
Eigen::Matrix3d
leastEntropyNeighbourhood(const std::vector<Eigen::Vector3f>& sorted_neighbours,
                          const NeighbourhoodSettings& settings, int& best_k, double& best_entropy)
{
  const int n = static_cast<int>(sorted_neighbours.size());
  const int k_last = std::min(settings.k_max, n);
  const Eigen::Vector3d origin = sorted_neighbours.front().cast<double>();
  const int k_first = (n < settings.k_min) ? n : settings.k_min;
  const int k_end = (n < settings.k_min) ? n : k_last;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_sq = Eigen::Matrix3d::Zero();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  best_entropy = std::numeric_limits<double>::infinity();
  best_k = 0;
  Eigen::Matrix3d best_cov = Eigen::Matrix3d::Zero();
  int next_k = k_first;
  for (int k = 1; k <= k_end; ++k) {
    const Eigen::Vector3d d = sorted_neighbours[k - 1].cast<double>() - origin;
    sum += d;
    sum_sq.noalias() += d * d.transpose();
    if (k != next_k)
      continue;
    next_k += settings.k_step;
    const Eigen::Matrix3d cov = covarianceFromMoments(sum, sum_sq, k);
    solver.computeDirect(cov, Eigen::EigenvaluesOnly);
    const double e = eigenEntropy(clampedEigenvalues(solver.eigenvalues()));
    if (best_k == 0 || e < best_entropy) {  // first tested k is the fallback for zero extent
      best_entropy = e;
      best_k = k;
      best_cov = cov;
    }
  }
  return best_cov;
}

/// Dimensionality features, residual, normal and principal direction from the covariance.
void
shapeFeatures(const Eigen::Matrix3d& cov, PointFeatures& f)
{
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(cov, Eigen::ComputeEigenvectors);
  const Eigen::Vector3d lambda = clampedEigenvalues(solver.eigenvalues());  // ascending
  const double s1 = std::sqrt(lambda[2]), s2 = std::sqrt(lambda[1]), s3 = std::sqrt(lambda[0]);
  if (!(s1 > 0.0) || !std::isfinite(s1)) {
    // Zero extent (duplicates): isotropic by convention, never linear or planar.
    f.a3d = 1.f;
    f.dimensionality = Dimensionality::Volumetric;
    return;
  }
  f.a1d = static_cast<float>((s1 - s2) / s1);
  f.a2d = static_cast<float>((s2 - s3) / s1);
  f.a3d = static_cast<float>(s3 / s1);
  f.residual = static_cast<float>(s3);  // RMS distance to the LS plane = √λ3 (1/k covariance)
  Eigen::Vector3f normal = solver.eigenvectors().col(0).cast<float>();
  if (normal.z() < 0.f)
    normal = -normal;
  f.normal = normal.normalized();
  f.principal = solver.eigenvectors().col(2).cast<float>().normalized();
  if (f.a2d >= f.a1d && f.a2d >= f.a3d)
    f.dimensionality = Dimensionality::Planar;
  else if (f.a1d >= f.a3d)
    f.dimensionality = Dimensionality::Linear;
  else
    f.dimensionality = Dimensionality::Volumetric;
}

}  // namespace

PointFeatures
computePointFeatures(const std::vector<Eigen::Vector3f>& sorted_neighbours,
                     const NeighbourhoodSettings& settings)
{
  PointFeatures f;
  const int n = static_cast<int>(sorted_neighbours.size());
  if (n < 3 || settings.k_min < 3 || settings.k_step < 1)
    return f;
  int best_k = 0;
  double best_entropy = 0.0;
  const Eigen::Matrix3d cov = leastEntropyNeighbourhood(sorted_neighbours, settings, best_k, best_entropy);
  f.k = static_cast<std::uint16_t>(best_k);
  f.entropy = static_cast<float>(best_entropy);
  shapeFeatures(cov, f);
  return f;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
