#include <pcl_ls3d/common/voxel_index.h>
#include <pcl_ls3d/estimators/neighbour_noise.h>
#include <pcl_ls3d/stats/descriptive.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {

namespace {
constexpr int kCandidates = 4;  // nearest points looked at for one at a distinct position
}  // namespace

double
neighbourDifferenceScale(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& residuals)
{
  const std::size_t n = std::min(points.size(), residuals.size());
  std::vector<Eigen::Vector3d> observed(n,
                                        Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (std::size_t i = 0; i < n; ++i)
    if (points[i].allFinite() && std::isfinite(residuals[i]))
      observed[i] = points[i];
  const double spacing = cloudSpacing(observed).spacing;
  if (!(spacing > 0.0))
    return 0.0;
  const VoxelIndex index(observed, 2.0 * spacing);
  std::vector<double> differences;
  differences.reserve(n);
  std::vector<int> near;
  for (std::size_t i = 0; i < n; ++i) {
    if (!observed[i].allFinite())
      continue;
    index.nearestK(observed[i], kCandidates, near);
    for (const int j : near) {
      const std::size_t u = static_cast<std::size_t>(j);
      if (u != i && (observed[u] - observed[i]).squaredNorm() > 0.0) {
        differences.push_back(std::abs(residuals[i] - residuals[u]));
        break;
      }
    }
  }
  if (differences.empty())
    return 0.0;
  return stats::kMadToSigma * stats::medianHigh(std::move(differences)) / std::sqrt(2.0);
}

}  // namespace pcl_ls3d
