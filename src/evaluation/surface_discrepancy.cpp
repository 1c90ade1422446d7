#include <pcl_ls3d/evaluation/surface_discrepancy.h>
#include <pcl_ls3d/stats/descriptive.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {
namespace evaluation {

SurfaceDiscrepancy::SurfaceDiscrepancy(const CloudXYZ::ConstPtr& target, const DiscrepancySettings& settings)
    : settings_(settings), target_(target)
{
  const std::size_t n = target ? target->size() : 0;
  centroid_.assign(n, Eigen::Vector3d::Zero());
  normal_.assign(n, Eigen::Vector3d::UnitZ());
  flat_.assign(n, 0);
  if (n == 0)
    return;
  tree_.setInputCloud(target);
  Eigen::Vector3d middle = Eigen::Vector3d::Zero();
  for (const auto& p : *target)
    middle += p.getVector3fMap().cast<double>();
  middle /= static_cast<double>(n);
  const int k = std::max(3, settings.k);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(n); ++i) {
    pcl::Indices idx;
    std::vector<float> d2;
    if (tree_.nearestKSearch((*target)[static_cast<std::size_t>(i)], k, idx, d2) < 3)
      continue;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (auto j : idx)
      c += (*target)[static_cast<std::size_t>(j)].getVector3fMap().cast<double>();
    c /= static_cast<double>(idx.size());
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    for (auto j : idx) {
      const Eigen::Vector3d d = (*target)[static_cast<std::size_t>(j)].getVector3fMap().cast<double>() - c;
      C += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
    const Eigen::Vector3d ev = es.eigenvalues();
    const double sum = ev.sum();
    Eigen::Vector3d nrm = es.eigenvectors().col(0);
    if (settings.outward ? nrm.dot(c - middle) < 0.0 : nrm.z() < 0.0)
      nrm = -nrm;
    const auto u = static_cast<std::size_t>(i);
    centroid_[u] = c;
    normal_[u] = nrm;
    flat_[u] = sum > 0.0 && ev[0] / sum <= settings.max_variation ? 1 : 0;
  }
}

std::size_t
SurfaceDiscrepancy::flatPlanes() const
{
  return static_cast<std::size_t>(std::count(flat_.begin(), flat_.end(), 1));
}

DiscrepancyStats
SurfaceDiscrepancy::evaluate(const Eigen::Matrix3Xd& source_points, const Eigen::Matrix4d& T) const
{
  DiscrepancyStats out;
  if (!target_ || target_->empty() || !T.allFinite())
    return out;
  const Eigen::Matrix3d A = T.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = T.topRightCorner<3, 1>();
  const double max_sq = settings_.max_distance * settings_.max_distance;
  const auto m = static_cast<std::ptrdiff_t>(source_points.cols());
  std::vector<double> d(static_cast<std::size_t>(m), std::numeric_limits<double>::quiet_NaN());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < m; ++i) {
    const Eigen::Vector3d y = A * source_points.col(i) + t;
    pcl::PointXYZ q(static_cast<float>(y.x()), static_cast<float>(y.y()), static_cast<float>(y.z()));
    pcl::Indices k(1);
    std::vector<float> d2(1);
    if (tree_.nearestKSearch(q, 1, k, d2) != 1 || d2[0] > max_sq)
      continue;
    const auto j = static_cast<std::size_t>(k[0]);
    if (flat_[j])
      d[static_cast<std::size_t>(i)] = normal_[j].dot(y - centroid_[j]);
  }
  std::vector<double> v;
  v.reserve(d.size());
  double sum_sq = 0.0;
  for (double x : d)
    if (std::isfinite(x)) {
      v.push_back(x);
      sum_sq += x * x;
    }
  out.points = v.size();
  if (v.empty())
    return out;
  out.median = stats::medianHigh(v);
  for (double& x : v)
    x = std::abs(x - out.median);
  out.sigma_mad = stats::kMadToSigma * stats::medianHigh(std::move(v));
  out.rms = std::sqrt(sum_sq / static_cast<double>(out.points));
  return out;
}

}  // namespace evaluation
}  // namespace pcl_ls3d
