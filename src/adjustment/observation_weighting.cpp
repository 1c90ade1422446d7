#include <pcl_ls3d/adjustment/observation_weighting.h>

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
  const std::size_t mid = a.size() / 2;
  std::nth_element(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(mid), a.end());
  return 1.4826 * a[mid];
}

}  // namespace pcl_ls3d
