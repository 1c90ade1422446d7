#include <pcl_ls3d/adjustment/observation_weighting.h>
#include <pcl_ls3d/stats/descriptive.h>

#include <vector>

namespace pcl_ls3d {

double
robustScale(const Eigen::VectorXd& l)
{
  if (l.size() == 0)
    return 0.0;
  std::vector<double> a(static_cast<std::size_t>(l.size()));
  for (Eigen::Index i = 0; i < l.size(); ++i)
    a[static_cast<std::size_t>(i)] = std::abs(l[i]);
  return stats::kMadToSigma * stats::medianHigh(std::move(a));
}

}  // namespace pcl_ls3d
