#include <pcl_ls3d/strips/footprints.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace pcl_ls3d {
namespace strips {

namespace {

// Points per unit area of a strip: counted on a coarse square grid, refined twice (the first
// grid's cells are too big for the footprint's edges; each refinement uses ~9 points per cell).
double
estimateDensity(const Strip& s)
{
  if (s.size() < 3)
    return 0.0;
  Eigen::Vector2f lo = s.points[0].head<2>(), hi = lo;
  for (const auto& p : s.points) {
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  }
  const double area = std::max(1e-12, static_cast<double>((hi - lo).prod()));
  double cell = 3.0 * std::sqrt(area / static_cast<double>(s.size()));
  double density = static_cast<double>(s.size()) / area;
  for (int pass = 0; pass < 2 && cell > 0.0; ++pass) {
    std::unordered_map<std::uint64_t, char> occupied;
    occupied.reserve(s.size() / 4);
    for (const auto& p : s.points) {
      const auto cx = static_cast<std::uint64_t>(std::floor((p.x() - lo.x()) / cell));
      const auto cy = static_cast<std::uint64_t>(std::floor((p.y() - lo.y()) / cell));
      occupied[(cy << 32) | cx] = 1;
    }
    density = static_cast<double>(s.size()) / (static_cast<double>(occupied.size()) * cell * cell);
    cell = 3.0 / std::sqrt(density);
  }
  return density;
}

}  // namespace

Footprints
Footprints::build(const std::vector<Strip>& strips, double cell)
{
  Footprints f;
  if (!(cell > 0.0)) {
    double sparsest = std::numeric_limits<double>::infinity();
    for (const Strip& s : strips)
      if (s.size() >= 3)
        sparsest = std::min(sparsest, estimateDensity(s));
    cell = std::isfinite(sparsest) && sparsest > 0.0 ? 3.0 / std::sqrt(sparsest) : 1.0;
  }
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Strip& s : strips)
    for (const auto& p : s.points) {
      const Eigen::Vector2d b = s.origin.head<2>() + p.head<2>().cast<double>();
      lo = lo.cwiseMin(b);
      hi = hi.cwiseMax(b);
    }
  f.cells_.resize(strips.size());
  if (!lo.allFinite())
    return f;
  return build(strips, maps::GridGeometry::covering(lo, hi, cell));
}

Footprints
Footprints::build(const std::vector<Strip>& strips, const maps::GridGeometry& grid)
{
  Footprints f;
  f.grid_ = grid;
  f.cells_.resize(strips.size());
  for (std::size_t k = 0; k < strips.size(); ++k) {
    std::unordered_map<std::uint64_t, std::uint32_t> count;
    for (std::size_t i = 0; i < strips[k].size(); ++i) {
      const Eigen::Vector3d b = strips[k].blockPoint(i);
      const std::int64_t id = f.cellId(b.x(), b.y());
      if (id >= 0)
        ++count[static_cast<std::uint64_t>(id)];
    }
    f.cells_[k].assign(count.begin(), count.end());
    std::sort(f.cells_[k].begin(), f.cells_[k].end());
  }
  return f;
}

double
Footprints::density(std::size_t strip) const
{
  const Cells& c = cells_[strip];
  std::size_t n = 0;
  for (const auto& kv : c)
    n += kv.second;
  return c.empty() ? 0.0 : static_cast<double>(n) / (static_cast<double>(c.size()) * grid_.cell * grid_.cell);
}

std::int64_t
Footprints::cellId(double x, double y) const
{
  int col = 0, row = 0;
  if (!grid_.cellOf(x, y, col, row))
    return -1;
  return static_cast<std::int64_t>(row) * grid_.cols + col;
}

std::vector<Overlap>
findOverlaps(const Footprints& f, double min_area)
{
  std::vector<Overlap> out;
  const double cell_area = f.cell() * f.cell();
  for (std::size_t i = 0; i < f.strips(); ++i)
    for (std::size_t j = i + 1; j < f.strips(); ++j) {
      // Sorted cell lists: one merge pass finds the common cells.
      const Footprints::Cells &a = f.cells(i), &b = f.cells(j);
      Overlap o;
      o.i = static_cast<int>(i);
      o.j = static_cast<int>(j);
      for (std::size_t p = 0, q = 0; p < a.size() && q < b.size();) {
        if (a[p].first < b[q].first)
          ++p;
        else if (b[q].first < a[p].first)
          ++q;
        else {
          o.cells.push_back(a[p].first);
          o.points_i += a[p].second;
          o.points_j += b[q].second;
          ++p;
          ++q;
        }
      }
      if (o.cells.empty())
        continue;
      o.common_cells = o.cells.size();
      o.area = static_cast<double>(o.common_cells) * cell_area;
      if (o.area < min_area) {
        o.used = false;
        char buf[160];
        std::snprintf(buf, sizeof(buf), "common area %.1f below the minimum %.1f (%zu cells of %.3g)", o.area,
                      min_area, o.common_cells, f.cell());
        o.skip_reason = buf;
      }
      out.push_back(std::move(o));
    }
  return out;
}

std::vector<int>
connectedParts(std::size_t strips, const std::vector<Overlap>& overlaps)
{
  std::vector<int> parent(strips);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int a) {
    while (parent[static_cast<std::size_t>(a)] != a)
      a = parent[static_cast<std::size_t>(a)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
    return a;
  };
  std::vector<bool> linked(strips, false);
  for (const Overlap& o : overlaps)
    if (o.used) {
      parent[static_cast<std::size_t>(find(o.i))] = find(o.j);
      linked[static_cast<std::size_t>(o.i)] = linked[static_cast<std::size_t>(o.j)] = true;
    }
  std::vector<int> part(strips, -1), label(strips, -1);
  int next = 0;
  for (std::size_t k = 0; k < strips; ++k) {
    if (!linked[k])
      continue;
    const int root = find(static_cast<int>(k));
    if (label[static_cast<std::size_t>(root)] < 0)
      label[static_cast<std::size_t>(root)] = next++;
    part[k] = label[static_cast<std::size_t>(root)];
  }
  return part;
}

}  // namespace strips
}  // namespace pcl_ls3d
