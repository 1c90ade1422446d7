#include <pcl_ls3d/adjustment/overlap_grid.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {

namespace {

/// The xy bounds of the target's finite points (empty: xmax < xmin).
struct Extent
{
  double xmin = std::numeric_limits<double>::max(), ymin = std::numeric_limits<double>::max();
  double xmax = std::numeric_limits<double>::lowest(), ymax = std::numeric_limits<double>::lowest();
};

Extent
horizontalExtent(const TargetSurface& target)
{
  Extent e;
  for (std::size_t i = 0; i < target.size(); ++i) {
    const Eigen::Vector3d p = target.point(static_cast<int>(i));
    if (!p.allFinite())
      continue;
    e.xmin = std::min(e.xmin, p.x());
    e.xmax = std::max(e.xmax, p.x());
    e.ymin = std::min(e.ymin, p.y());
    e.ymax = std::max(e.ymax, p.y());
  }
  return e;
}

/// The cells' layout: origin, inverse edge and counts.
struct CellLayout
{
  double x0, y0, inv_cell;
  long nx, ny;

  std::size_t
  size() const
  {
    return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  }
};

/// The z range of the target's points in each cell (empty cells: lo > hi).
void
cellZRanges(const TargetSurface& target, const CellLayout& g, std::vector<float>& lo, std::vector<float>& hi)
{
  lo.assign(g.size(), std::numeric_limits<float>::max());
  hi.assign(g.size(), std::numeric_limits<float>::lowest());
  for (std::size_t i = 0; i < target.size(); ++i) {
    const Eigen::Vector3d p = target.point(static_cast<int>(i));
    if (!p.allFinite())
      continue;
    const long cx = std::min(g.nx - 1, static_cast<long>((p.x() - g.x0) * g.inv_cell));
    const long cy = std::min(g.ny - 1, static_cast<long>((p.y() - g.y0) * g.inv_cell));
    const std::size_t c = static_cast<std::size_t>(cy * g.nx + cx);
    lo[c] = std::min(lo[c], static_cast<float>(p.z()));
    hi[c] = std::max(hi[c], static_cast<float>(p.z()));
  }
}

/// The z ranges dilated by one cell (3 × 3) and grown by `grow`.
void
dilateZRanges(const CellLayout& g, const std::vector<float>& lo, const std::vector<float>& hi, float grow,
              std::vector<float>& zlo, std::vector<float>& zhi)
{
  zlo.assign(g.size(), std::numeric_limits<float>::max());
  zhi.assign(g.size(), std::numeric_limits<float>::lowest());
  for (long y = 0; y < g.ny; ++y)
    for (long x = 0; x < g.nx; ++x) {
      float a = std::numeric_limits<float>::max(), b = std::numeric_limits<float>::lowest();
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx) {
          const long u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= g.nx || v >= g.ny)
            continue;
          const std::size_t c = static_cast<std::size_t>(v * g.nx + u);
          a = std::min(a, lo[c]);
          b = std::max(b, hi[c]);
        }
      const std::size_t c = static_cast<std::size_t>(y * g.nx + x);
      if (a <= b) {
        zlo[c] = a - grow;
        zhi[c] = b + grow;
      }
    }
}

}  // namespace

bool
OverlapGrid::build(const TargetSurface& target, double reach, std::size_t max_cells)
{
  built_ = false;
  if (!(reach > 0.0) || !std::isfinite(reach) || target.size() == 0)
    return false;
  const Extent e = horizontalExtent(target);
  if (!(e.xmax >= e.xmin))
    return false;
  // A reach beyond the target's extent (e.g. the "unlimited" default) culls nothing useful.
  if (!(reach < std::hypot(e.xmax - e.xmin, e.ymax - e.ymin)))
    return false;
  // Cell edge >= reach, so a dilation by one cell covers every point within reach.
  double cell = reach;
  const double w = e.xmax - e.xmin + 2.0 * reach, h = e.ymax - e.ymin + 2.0 * reach;
  while ((w / cell + 1.0) * (h / cell + 1.0) > static_cast<double>(max_cells))
    cell *= 2.0;
  x0_ = e.xmin - reach;
  y0_ = e.ymin - reach;
  inv_cell_ = 1.0 / cell;
  nx_ = static_cast<long>(std::floor(w / cell)) + 1;
  ny_ = static_cast<long>(std::floor(h / cell)) + 1;
  const CellLayout layout{x0_, y0_, inv_cell_, nx_, ny_};
  std::vector<float> lo, hi;
  cellZRanges(target, layout, lo, hi);
  // Grow the z range by reach (float rounding margin included).
  const float grow = static_cast<float>(reach) * 1.0001f + 1e-3f;
  dilateZRanges(layout, lo, hi, grow, zlo_, zhi_);
  built_ = true;
  return true;
}

}  // namespace pcl_ls3d
