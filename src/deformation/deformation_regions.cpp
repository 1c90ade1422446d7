#include <pcl_ls3d/common/voxel_index.h>
#include <pcl_ls3d/deformation/deformation_regions.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

namespace pcl_ls3d {
namespace deformation {

namespace {

/// Union-find with path halving.
struct DisjointSets
{
  explicit DisjointSets(std::size_t n) : parent(n)
  {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int
  find(int a)
  {
    while (parent[static_cast<std::size_t>(a)] != a)
      a = parent[static_cast<std::size_t>(a)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
    return a;
  }
  void
  unite(int a, int b)
  {
    a = find(a);
    b = find(b);
    if (a != b)
      parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  std::vector<int> parent;
};

/// Cell key of a point on the plane with normal axis `axis`.
std::int64_t
cellKey(const Eigen::Vector3d& p, int axis, double cell)
{
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  const auto u = static_cast<std::int64_t>(std::floor(p[a] / cell));
  const auto v = static_cast<std::int64_t>(std::floor(p[b] / cell));
  // Unsigned: shifting a negative value left is undefined before C++20.
  return static_cast<std::int64_t>((static_cast<std::uint64_t>(u) << 32) ^
                                   (static_cast<std::uint64_t>(v) & 0xffffffffu));
}

/// Statistics of one connected set of points.
DeformationRegion
describe(const std::vector<int>& members, const std::vector<Eigen::Vector3d>& points,
         const ResidualField& field, int axis, double cell)
{
  DeformationRegion r;
  r.points = members.size();
  r.max = -std::numeric_limits<double>::infinity();
  r.min = std::numeric_limits<double>::infinity();
  std::unordered_map<std::int64_t, std::pair<double, int>> cells;  // Σ r, count per cell
  double sum = 0.0;
  r.box_min = r.box_max = points[static_cast<std::size_t>(members.front())];
  for (const int i : members) {
    const std::size_t u = static_cast<std::size_t>(i);
    const double v = field.residual[u];
    sum += v;
    r.max = std::max(r.max, v);
    r.min = std::min(r.min, v);
    r.centroid += points[u];
    r.box_min = r.box_min.cwiseMin(points[u]);
    r.box_max = r.box_max.cwiseMax(points[u]);
    auto& c = cells[cellKey(points[u], axis, cell)];
    c.first += v;
    ++c.second;
  }
  r.mean = sum / static_cast<double>(members.size());
  r.sign = r.mean >= 0.0 ? 1 : -1;
  r.centroid /= static_cast<double>(members.size());
  r.area = static_cast<double>(cells.size()) * cell * cell;
  for (const auto& c : cells)
    r.volume += c.second.first / c.second.second * cell * cell;
  return r;
}

// Positions the regions are linked on: in the area plane when one is given (LZD heights: on a
// surface sampled more densely than its noise, a point's 3-D neighbours within the adjacency
// are few, and 3-D links cut a deformed patch into pieces below min_points), else in 3-D.
std::vector<Eigen::Vector3d>
linkPositions(const std::vector<Eigen::Vector3d>& points, int plane_axis)
{
  std::vector<Eigen::Vector3d> out = points;
  if (plane_axis >= 0 && plane_axis < 3)
    for (Eigen::Vector3d& p : out)
      p[plane_axis] = 0.0;
  return out;
}

/// Hysteresis: each kept region takes in, breadth first, the points within `adjacency` of one of
/// its points that are not significant, have the region's sign and |r| > grow_k σ_i; a point
/// joins the first region that reaches it.
void
growRegions(std::vector<std::vector<int>>& kept, const std::vector<Eigen::Vector3d>& points,
            const ResidualField& field, double adjacency, double grow_k)
{
  const std::size_t n = points.size();
  std::vector<Eigen::Vector3d> weak(n, Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (std::size_t i = 0; i < n; ++i)
    if (!field.significant[i] && std::isfinite(field.residual[i]) &&
        std::abs(field.residual[i]) > grow_k * field.sigma[i])
      weak[i] = points[i];
  const VoxelIndex index(weak, std::max(adjacency, 1e-9));
  std::vector<int> near;
  for (std::vector<int>& members : kept) {
    const bool up = field.residual[static_cast<std::size_t>(members.front())] > 0.0;
    for (std::size_t head = 0; head < members.size(); ++head) {
      index.radiusSearch(points[static_cast<std::size_t>(members[head])], adjacency, near);
      for (const int j : near) {
        Eigen::Vector3d& w = weak[static_cast<std::size_t>(j)];
        if (!w.allFinite() || (field.residual[static_cast<std::size_t>(j)] > 0.0) != up)
          continue;
        w = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());  // taken
        members.push_back(j);
      }
    }
  }
}

}  // namespace

bool
RegionSettings::isValid(std::string* why) const
{
  auto bad = [why](const char* reason) {
    if (why)
      *why = reason;
    return false;
  };
  if (min_points < 1)
    return bad("min_points must be >= 1");
  if (plane_axis < -1 || plane_axis > 2)
    return bad("plane_axis must be -1, 0, 1 or 2");
  if (!(adjacency >= 0.0) || !(cell >= 0.0) || !std::isfinite(adjacency) || !std::isfinite(cell))
    return bad("adjacency and cell must be finite and >= 0");
  if (!(grow_k >= 0.0) || !std::isfinite(grow_k))
    return bad("grow_k must be finite and >= 0 (0: no hysteresis)");
  return true;
}

namespace {

// The observed points' spacing, plane and cell, and the observed area (cells holding a residual).
// False when no cell size follows from the data.
bool
measureObserved(const std::vector<Eigen::Vector3d>& points, const ResidualField& field,
                const RegionSettings& s, RegionAnalysis& out)
{
  const std::size_t n = points.size();
  std::vector<Eigen::Vector3d> observed(n,
                                        Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(field.residual[i]))
      observed[i] = points[i];
  const CloudSpacing sp = cloudSpacing(observed, s.plane_axis);
  out.spacing = sp.spacing;
  out.plane_normal_axis = sp.normal_axis;
  out.adjacency = s.adjacency > 0.0 ? s.adjacency : 2.5 * sp.spacing;
  out.cell = s.cell > 0.0 ? s.cell : sp.spacing;
  if (!(out.cell > 0.0))
    return false;
  std::unordered_set<std::int64_t> cells;
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(field.residual[i]))
      cells.insert(cellKey(points[i], sp.normal_axis, out.cell));
  out.area_observed = static_cast<double>(cells.size()) * out.cell * out.cell;
  return true;
}

// Significant points of each sign, linked within the adjacency distance: the groups by their root.
std::unordered_map<int, std::vector<int>>
linkSignificant(const std::vector<Eigen::Vector3d>& link, const ResidualField& field, double adjacency)
{
  const std::size_t n = link.size();
  std::vector<Eigen::Vector3d> flagged(n,
                                       Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (std::size_t i = 0; i < n; ++i)
    if (field.significant[i] && std::isfinite(field.residual[i]))
      flagged[i] = link[i];
  const VoxelIndex index(flagged, std::max(adjacency, 1e-9));
  DisjointSets sets(n);
  std::vector<int> near;
  for (std::size_t i = 0; i < n; ++i) {
    if (!flagged[i].allFinite())
      continue;
    index.radiusSearch(flagged[i], adjacency, near);
    for (const int j : near)
      if ((field.residual[i] > 0.0) == (field.residual[static_cast<std::size_t>(j)] > 0.0))
        sets.unite(static_cast<int>(i), j);
  }
  std::unordered_map<int, std::vector<int>> groups;
  for (std::size_t i = 0; i < n; ++i)
    if (flagged[i].allFinite())
      groups[sets.find(static_cast<int>(i))].push_back(static_cast<int>(i));
  return groups;
}

// Ids by decreasing area (ties: more points, then the smallest first index), deterministic; the
// deformed area is that of the cells the regions' points fall in.
void
numberRegions(const std::vector<std::vector<int>>& kept, const std::vector<Eigen::Vector3d>& points,
              RegionAnalysis& out)
{
  std::vector<std::size_t> order(kept.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const auto& ra = out.regions[a];
    const auto& rb = out.regions[b];
    if (ra.area != rb.area)
      return ra.area > rb.area;
    if (ra.points != rb.points)
      return ra.points > rb.points;
    return *std::min_element(kept[a].begin(), kept[a].end()) <
           *std::min_element(kept[b].begin(), kept[b].end());
  });
  std::vector<DeformationRegion> sorted;
  std::unordered_set<std::int64_t> deformed_cells;
  for (std::size_t k = 0; k < order.size(); ++k) {
    DeformationRegion r = out.regions[order[k]];
    r.id = static_cast<int>(k) + 1;
    for (const int i : kept[order[k]]) {
      out.region[static_cast<std::size_t>(i)] = r.id;
      deformed_cells.insert(cellKey(points[static_cast<std::size_t>(i)], out.plane_normal_axis, out.cell));
    }
    sorted.push_back(r);
  }
  out.regions = std::move(sorted);
  out.area_deformed = static_cast<double>(deformed_cells.size()) * out.cell * out.cell;
}

}  // namespace

RegionAnalysis
analyseRegions(const std::vector<Eigen::Vector3d>& points, const ResidualField& field,
               const RegionSettings& s)
{
  RegionAnalysis out;
  out.region.assign(points.size(), 0);
  if (!measureObserved(points, field, s, out))
    return out;
  const std::vector<Eigen::Vector3d> link = linkPositions(points, s.plane_axis);
  // Groups of at least min_points are regions; smaller ones are noise.
  std::vector<std::vector<int>> kept;
  for (auto& g : linkSignificant(link, field, out.adjacency)) {
    if (g.second.size() >= s.min_points)
      kept.push_back(std::move(g.second));
    else {
      DeformationRegion r = describe(g.second, points, field, out.plane_normal_axis, out.cell);
      r.id = -1;
      for (const int i : g.second)
        out.region[static_cast<std::size_t>(i)] = -1;
      out.noise.push_back(r);
    }
  }
  if (s.grow_k > 0.0)
    growRegions(kept, link, field, out.adjacency, s.grow_k);
  for (const auto& members : kept)
    out.regions.push_back(describe(members, points, field, out.plane_normal_axis, out.cell));
  numberRegions(kept, points, out);
  std::sort(out.noise.begin(), out.noise.end(),
            [](const DeformationRegion& a, const DeformationRegion& b) { return a.points > b.points; });
  out.percent_deformed = out.area_observed > 0.0 ? 100.0 * out.area_deformed / out.area_observed : 0.0;
  return out;
}

}  // namespace deformation
}  // namespace pcl_ls3d
