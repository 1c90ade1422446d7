#include <pcl_ls3d/adjustment/overlap_grid.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {

bool
OverlapGrid::build(const TargetSurface& target, double reach, std::size_t max_cells)
{
  built_ = false;
  if (!(reach > 0.0) || !std::isfinite(reach) || target.size() == 0)
    return false;
  double xmin = std::numeric_limits<double>::max(), ymin = xmin;
  double xmax = std::numeric_limits<double>::lowest(), ymax = xmax;
  for (std::size_t i = 0; i < target.size(); ++i) {
    const Eigen::Vector3d p = target.point(static_cast<int>(i));
    if (!p.allFinite())
      continue;
    xmin = std::min(xmin, p.x());
    xmax = std::max(xmax, p.x());
    ymin = std::min(ymin, p.y());
    ymax = std::max(ymax, p.y());
  }
  if (!(xmax >= xmin))
    return false;
  // A reach beyond the target's extent (e.g. the "unlimited" default) culls nothing useful.
  if (!(reach < std::hypot(xmax - xmin, ymax - ymin)))
    return false;
  // Cell edge >= reach, so a dilation by one cell covers every point within reach.
  double cell = reach;
  const double w = xmax - xmin + 2.0 * reach, h = ymax - ymin + 2.0 * reach;
  while ((w / cell + 1.0) * (h / cell + 1.0) > static_cast<double>(max_cells))
    cell *= 2.0;
  x0_ = xmin - reach;
  y0_ = ymin - reach;
  inv_cell_ = 1.0 / cell;
  nx_ = static_cast<long>(std::floor(w / cell)) + 1;
  ny_ = static_cast<long>(std::floor(h / cell)) + 1;
  const std::size_t n = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  std::vector<float> lo(n, std::numeric_limits<float>::max()), hi(n, std::numeric_limits<float>::lowest());
  for (std::size_t i = 0; i < target.size(); ++i) {
    const Eigen::Vector3d p = target.point(static_cast<int>(i));
    if (!p.allFinite())
      continue;
    const long cx = std::min(nx_ - 1, static_cast<long>((p.x() - x0_) * inv_cell_));
    const long cy = std::min(ny_ - 1, static_cast<long>((p.y() - y0_) * inv_cell_));
    const std::size_t c = static_cast<std::size_t>(cy * nx_ + cx);
    lo[c] = std::min(lo[c], static_cast<float>(p.z()));
    hi[c] = std::max(hi[c], static_cast<float>(p.z()));
  }
  // Dilate by one cell (3 × 3) and grow the z range by reach (float rounding margin included).
  const float grow = static_cast<float>(reach) * 1.0001f + 1e-3f;
  zlo_.assign(n, std::numeric_limits<float>::max());
  zhi_.assign(n, std::numeric_limits<float>::lowest());
  for (long y = 0; y < ny_; ++y)
    for (long x = 0; x < nx_; ++x) {
      float a = std::numeric_limits<float>::max(), b = std::numeric_limits<float>::lowest();
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx) {
          const long u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= nx_ || v >= ny_)
            continue;
          const std::size_t c = static_cast<std::size_t>(v * nx_ + u);
          a = std::min(a, lo[c]);
          b = std::max(b, hi[c]);
        }
      const std::size_t c = static_cast<std::size_t>(y * nx_ + x);
      if (a <= b) {
        zlo_[c] = a - grow;
        zhi_[c] = b + grow;
      }
    }
  built_ = true;
  return true;
}

}  // namespace pcl_ls3d
