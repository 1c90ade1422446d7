#include <pcl_ls3d/strips/strip.h>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {
namespace strips {

std::size_t
Strip::observableCount() const
{
  return static_cast<std::size_t>(std::count(observable.begin(), observable.end(), std::uint8_t(1)));
}

bool
Strip::classified() const
{
  std::size_t n = 0, with_class = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (observable[i]) {
      ++n;
      with_class += classification[i] > 1;
    }
  return n > 0 && 2 * with_class > n;
}

Strip
makeStrip(std::string name, int point_source_id, const std::vector<Eigen::Vector3d>& block_points,
          std::vector<std::uint8_t> classification, std::vector<std::uint8_t> observable)
{
  Strip s;
  s.name = std::move(name);
  s.point_source_id = point_source_id;
  const std::size_t n = block_points.size();
  s.classification = classification.size() == n ? std::move(classification) : std::vector<std::uint8_t>(n, 0);
  s.observable = observable.size() == n ? std::move(observable) : std::vector<std::uint8_t>(n, 1);
  if (n == 0)
    return s;
  Eigen::Vector2d lo = block_points[0].head<2>(), hi = lo;
  double z = 0.0;
  for (const auto& p : block_points) {
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
    z += p.z();
  }
  const Eigen::Vector2d c = 0.5 * (lo + hi);
  s.origin = Eigen::Vector3d(std::round(c.x()), std::round(c.y()), std::round(z / static_cast<double>(n)));
  s.points.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    s.points[i] = (block_points[i] - s.origin).cast<float>();
  return s;
}

}  // namespace strips
}  // namespace pcl_ls3d
