/// \file segment_kinds.cpp
/// \brief Segment shapes and kinds.

#include <pcl_ls3d/segmentation/segment_kinds.h>
#include <pcl_ls3d/stats/descriptive.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {
namespace segmentation {

std::vector<SegmentShape>
segmentShapes(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
              const std::vector<float>& residuals, const std::vector<char>& ground)
{
  const int n_seg = labels.empty() ? 0 : *std::max_element(labels.begin(), labels.end()) + 1;
  std::vector<SegmentShape> shapes(static_cast<std::size_t>(std::max(0, n_seg)));
  // Moments relative to the first point of each segment keep float coordinates well scaled.
  std::vector<Eigen::Vector3d> anchor(shapes.size(), Eigen::Vector3d::Zero());
  std::vector<char> anchored(shapes.size(), 0);
  std::vector<Eigen::Vector3d> sum(shapes.size(), Eigen::Vector3d::Zero());
  std::vector<Eigen::Matrix3d> sum_sq(shapes.size(), Eigen::Matrix3d::Zero());
  for (std::size_t p = 0; p < labels.size(); ++p) {
    if (labels[p] < 0)
      continue;
    const auto s = static_cast<std::size_t>(labels[p]);
    if (!anchored[s]) {
      anchor[s] = points[p].cast<double>();
      anchored[s] = 1;
    }
    SegmentShape& sh = shapes[s];
    const Eigen::Vector3d d = points[p].cast<double>() - anchor[s];
    ++sh.n;
    sh.ground += ground[p] != 0;
    sum[s] += d;
    sum_sq[s].noalias() += d * d.transpose();
  }
  std::vector<std::vector<double>> r(shapes.size());
  for (std::size_t p = 0; p < labels.size(); ++p)
    if (labels[p] >= 0)
      r[static_cast<std::size_t>(labels[p])].push_back(residuals[p]);
  for (std::size_t s = 0; s < shapes.size(); ++s)
    shapes[s].median_residual = r[s].empty() ? 0.0 : stats::median(std::move(r[s]));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    SegmentShape& sh = shapes[s];
    if (sh.n < 3)
      continue;
    const Eigen::Vector3d mean = sum[s] / static_cast<double>(sh.n);
    es.computeDirect(sum_sq[s] / static_cast<double>(sh.n) - mean * mean.transpose());
    sh.lambda = es.eigenvalues().cwiseMax(0.0);
    sh.normal = es.eigenvectors().col(0);
    sh.principal = es.eigenvectors().col(2);
  }
  return shapes;
}

SegmentKind
kindOf(const SegmentShape& sh, double ground_residual, const KindSettings& s)
{
  if (2 * sh.ground > sh.n)
    return SegmentKind::Ground;
  const double l1 = sh.lambda[2], l2 = sh.lambda[1], l3 = sh.lambda[0];
  if (sh.n >= 3 && l1 > 0.0 && std::sqrt(l2 / l1) < s.linear_ratio)
    return SegmentKind::Linear;
  // Flat at its own scale: a surface, however rough its points (a facade with windows and
  // recesses, a gravel roof); vegetation is volumetric at the segment's scale.
  const bool flat = sh.n >= 3 && l2 > 0.0 && std::sqrt(l3 / l2) < s.flat_ratio;
  if (!flat && hasRoughPoints(sh, ground_residual, s))
    return SegmentKind::Rough;
  if (flat && std::abs(sh.normal.z()) < s.wall_normal_z)
    return SegmentKind::Wall;
  return SegmentKind::Solid;
}

bool
hasRoughPoints(const SegmentShape& sh, double ground_residual, const KindSettings& s)
{
  return sh.median_residual > s.roughness_ratio * ground_residual;
}

double
groundResidual(const std::vector<float>& residuals, const std::vector<char>& ground)
{
  std::vector<double> g, all;
  for (std::size_t p = 0; p < residuals.size(); ++p) {
    all.push_back(residuals[p]);
    if (ground[p])
      g.push_back(residuals[p]);
  }
  return stats::median(g.size() >= 10 ? g : all);
}

}  // namespace segmentation
}  // namespace pcl_ls3d
