#include "matching_steps.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace detail {

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

bool
changesBelow(const GaussMarkovSolution& sol, double fraction)
{
  for (int i = 0; i < 7; ++i)
    if (sol.determinable[static_cast<std::size_t>(i)] &&
        std::abs(sol.dx[i]) > fraction * sol.sigma0 * std::sqrt(sol.qxx(i, i)))
      return false;
  return true;
}

double
robustScale(const std::vector<double>& l, std::size_t m)
{
  std::vector<double> a(l.begin(), l.begin() + static_cast<std::ptrdiff_t>(m));
  for (double& x : a)
    x = std::abs(x);
  std::nth_element(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(m / 2), a.end());
  return 1.4826 * a[m / 2];
}

std::string
fillPrecision(AdjustmentReport& report, const GaussMarkovSolution& sol)
{
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
  return undetermined;
}

}  // namespace detail
}  // namespace pcl_ls3d
