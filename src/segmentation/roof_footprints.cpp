/// \file roof_footprints.cpp
/// \brief The footprint rules of the object assembly: plan cells of buildings, touching roofs,
///        and what lies on or under a roof.

#include "roof_footprints.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <unordered_map>

namespace pcl_ls3d {
namespace segmentation {
namespace detail {
namespace {

/// Horizontal grid cell key of a point (cells of \a cell; 2^21 cells per axis around 0).
std::int64_t
cellKey(const Eigen::Vector3f& p, double cell, int dx = 0, int dy = 0)
{
  const auto ix = static_cast<std::int64_t>(std::floor(p.x() / cell)) + dx + (1 << 20);
  const auto iy = static_cast<std::int64_t>(std::floor(p.y() / cell)) + dy + (1 << 20);
  return (ix << 22) | iy;
}

/// Two buildings whose roofs touch in plan (at least \a min_contacts cells of one within
/// \a reach cells of the other) are one building: a roof step, where the wall between the
/// levels holds too few points for the k-NN links, or an annex under the main roof's eaves.
void
joinTouchingRoofs(const std::unordered_map<std::int64_t, int>& own, int reach, std::size_t min_contacts,
                  Groups& groups)
{
  std::map<std::pair<int, int>, std::size_t> contacts;
  for (const auto& [key, a] : own) {
    std::vector<int> seen;
    for (int dx = -reach; dx <= reach; ++dx)
      for (int dy = -reach; dy <= reach; ++dy) {
        const auto it = own.find(key + dx * (std::int64_t{1} << 22) + dy);  // dx < 0: no shift
        if (it != own.end() && it->second != a &&
            std::find(seen.begin(), seen.end(), it->second) == seen.end()) {
          seen.push_back(it->second);
          ++contacts[{std::min(a, it->second), std::max(a, it->second)}];
        }
      }
  }
  for (const auto& [pair, count] : contacts)
    if (count >= min_contacts)
      groups.unite(pair.first, pair.second);
}

/// A building's plan cell: the building group and the top of its roof or walls there.
struct RoofCell
{
  int root = -1;
  float top = 0.f;
  bool margin = false;  ///< within reach of the building's cells, no roof or wall point in it
};

/// Per horizontal cell: the building group (most of its points in roof or wall segments, or
/// flagged in \a building by an earlier pass; per segment, updated here) with most points in
/// it, spread over the cells within \a reach of it (a cell keeps its own), and that building's
/// highest structural point in the cell (spread cells: in the cells they spread from).
std::unordered_map<std::int64_t, RoofCell>
buildingFootprints(const Contacts& c, const std::vector<SegmentKind>& kind,
                   const std::vector<std::size_t>& size, double cell, int reach, std::size_t min_contacts,
                   Groups& groups, std::vector<char>& building)
{
  std::vector<std::size_t> structural_points(size.size(), 0);
  for (std::size_t p = 0; p < c.labels.size(); ++p)
    if (c.labels[p] >= 0 && structural(kind[static_cast<std::size_t>(c.labels[p])]))
      ++structural_points[static_cast<std::size_t>(groups.find(c.labels[p]))];
  // A group is a building while most of its points are in roofs and walls, and stays one
  // after what hangs under its roof has joined it (a rough facade may outweigh a roof strip).
  std::vector<char> is_building(size.size(), 0);
  for (std::size_t r = 0; r < size.size(); ++r)
    is_building[r] = 2 * structural_points[r] > size[r];
  for (std::size_t i = 0; i < size.size(); ++i)
    if (building[i])
      is_building[static_cast<std::size_t>(groups.find(static_cast<int>(i)))] = 1;
  for (std::size_t i = 0; i < size.size(); ++i)
    building[i] = is_building[static_cast<std::size_t>(groups.find(static_cast<int>(i)))];
  std::unordered_map<std::int64_t, std::map<int, std::size_t>> count;
  for (std::size_t p = 0; p < c.labels.size(); ++p) {
    if (c.labels[p] < 0 || !structural(kind[static_cast<std::size_t>(c.labels[p])]))
      continue;
    const auto root = static_cast<std::size_t>(groups.find(c.labels[p]));
    if (is_building[root])
      ++count[cellKey(c.points[p], cell)][static_cast<int>(root)];
  }
  std::unordered_map<std::int64_t, RoofCell> own, spread;
  for (const auto& [key, by_root] : count)
    own[key].root = std::max_element(by_root.begin(), by_root.end(), [&size](auto& a, auto& b) {
                      return a.second < b.second || (a.second == b.second && size[a.first] < size[b.first]);
                    })->first;
  std::unordered_map<std::int64_t, int> owner;
  for (const auto& [key, rc] : own)
    owner[key] = rc.root;
  joinTouchingRoofs(owner, reach, min_contacts, groups);
  for (auto& [key, rc] : own) {
    rc.root = groups.find(rc.root);
    rc.top = -std::numeric_limits<float>::infinity();
  }
  for (std::size_t p = 0; p < c.labels.size(); ++p) {
    if (c.labels[p] < 0 || !structural(kind[static_cast<std::size_t>(c.labels[p])]))
      continue;
    const auto it = own.find(cellKey(c.points[p], cell));
    if (it != own.end() && it->second.root == groups.find(c.labels[p]))
      it->second.top = std::max(it->second.top, c.points[p].z());
  }
  for (const auto& [key, rc] : own)
    for (int dx = -reach; dx <= reach; ++dx)
      for (int dy = -reach; dy <= reach; ++dy) {
        const std::int64_t to = key + dx * (std::int64_t{1} << 22) + dy;
        if (own.count(to))
          continue;
        RoofCell edge = rc;
        edge.margin = true;
        const auto [it, fresh] = spread.emplace(to, edge);
        if (!fresh && it->second.root == rc.root)
          it->second.top = std::max(it->second.top, rc.top);
      }
  for (const auto& [key, rc] : own)
    spread[key] = rc;
  return spread;
}

/// The groups with points in each margin cell of a footprint, and the cells the data cover.
struct PlanOccupancy
{
  std::unordered_map<std::int64_t, std::vector<int>> roots;  ///< margin cell -> groups in it
  std::int64_t lo_x = std::numeric_limits<std::int64_t>::max(), hi_x = -1;
  std::int64_t lo_y = std::numeric_limits<std::int64_t>::max(), hi_y = -1;

  bool
  inside(std::int64_t key) const
  {
    const std::int64_t x = key >> 22, y = key & ((std::int64_t{1} << 22) - 1);
    return x >= lo_x && x <= hi_x && y >= lo_y && y <= hi_y;
  }
  bool
  holds(std::int64_t key, int root) const
  {
    const auto it = roots.find(key);
    return it != roots.end() && std::find(it->second.begin(), it->second.end(), root) != it->second.end();
  }
};

PlanOccupancy
planOccupancy(const Contacts& c, double cell, const std::unordered_map<std::int64_t, RoofCell>& footprint,
              Groups& groups)
{
  PlanOccupancy o;
  for (std::size_t p = 0; p < c.points.size(); ++p) {
    const std::int64_t key = cellKey(c.points[p], cell);
    o.lo_x = std::min(o.lo_x, key >> 22);
    o.hi_x = std::max(o.hi_x, key >> 22);
    o.lo_y = std::min(o.lo_y, key & ((std::int64_t{1} << 22) - 1));
    o.hi_y = std::max(o.hi_y, key & ((std::int64_t{1} << 22) - 1));
    if (c.labels[p] < 0)
      continue;
    const auto f = footprint.find(key);
    if (f == footprint.end() || !f->second.margin)
      continue;
    const int root = groups.find(c.labels[p]);
    auto& at = o.roots[key];
    if (std::find(at.begin(), at.end(), root) == at.end())
      at.push_back(root);
  }
  return o;
}

/// Does margin cell \a key of building \a b open onto what lies beyond b's roof, seen from
/// group \a g: is one of its four neighbour cells inside the data neither a cell of b's roof nor
/// a margin cell of b holding g's points? A chimney or roof unit hides the roof under itself, so
/// the cells it covers hold no roof point; they are enclosed by roof cells and by each other.
/// Beyond the data's edge nothing is known (a roof cut by the tile edge may go on).
bool
opensBeyondRoof(std::int64_t key, int b, int g, const std::unordered_map<std::int64_t, RoofCell>& footprint,
                const PlanOccupancy& occupancy)
{
  constexpr std::pair<int, int> kSides[] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (const auto& [dx, dy] : kSides) {
    const std::int64_t to = key + dx * (std::int64_t{1} << 22) + dy;
    if (!occupancy.inside(to))
      continue;
    const auto f = footprint.find(to);
    const bool of_b = f != footprint.end() && f->second.root == b;
    if (of_b && (!f->second.margin || occupancy.holds(to, g)))
      continue;
    return true;
  }
  return false;
}

}  // namespace

/// A non-ground group whose points lie (footprint_share of them) on or under one building's
/// roof in plan, within footprint_margin of it, joins it if it is at most
/// enclosure_size_ratio of that building (chimneys and roof units: dense blobs whose k-NN links
/// stay inside themselves) or if those points also lie below the building's roof or walls in
/// their cell, whatever its size: a facade with balconies under the eaves of a roof that the
/// tile edge cut to a strip. A tree beside a house has most of its crown outside the
/// footprint; a crown over a roof lies above it and stays bound by the size ratio. Above the
/// roof, only what stands on it counts: a point higher than the roof in a margin cell that opens
/// onto what lies beyond the roof (opensBeyondRoof) is off the footprint. The margin is for what
/// hangs under the eaves; a crown overhanging the eave is above it and beyond the edge, a
/// chimney stands on the roof's own cells and on those it hides.
void
attachUnderRoofs(const Contacts& c, const std::vector<SegmentKind>& kind, const AssemblySettings& s,
                 Groups& groups, std::vector<char>& building)
{
  const std::size_t n = kind.size();
  std::vector<std::size_t> size(n, 0);
  std::vector<char> eligible(n, 1);
  for (std::size_t p = 0; p < c.labels.size(); ++p)
    if (c.labels[p] >= 0)
      ++size[static_cast<std::size_t>(groups.find(c.labels[p]))];
  for (std::size_t i = 0; i < n; ++i)
    if (kind[i] == SegmentKind::Ground)
      eligible[static_cast<std::size_t>(groups.find(static_cast<int>(i)))] = 0;
  const double cell = std::sqrt(c.max_sq);
  const int reach = static_cast<int>(std::ceil(s.footprint_margin / cell));
  const auto footprint = buildingFootprints(c, kind, size, cell, reach, s.min_links, groups, building);
  std::fill(size.begin(), size.end(), 0);  // touching roofs may have joined
  for (std::size_t p = 0; p < c.labels.size(); ++p)
    if (c.labels[p] >= 0)
      ++size[static_cast<std::size_t>(groups.find(c.labels[p]))];
  const PlanOccupancy occupancy = planOccupancy(c, cell, footprint, groups);
  // (group, building) -> points in the footprint, and those of them below the roof
  std::map<std::pair<int, int>, std::pair<std::size_t, std::size_t>> under;
  for (std::size_t p = 0; p < c.labels.size(); ++p) {
    if (c.labels[p] < 0)
      continue;
    const int root = groups.find(c.labels[p]);
    const auto it = footprint.find(cellKey(c.points[p], cell));
    if (!eligible[static_cast<std::size_t>(root)] || it == footprint.end() || it->second.root == root)
      continue;
    const bool below = c.points[p].z() < it->second.top;
    if (it->second.margin && !below &&
        opensBeyondRoof(it->first, it->second.root, root, footprint, occupancy))
      continue;
    auto& count = under[{root, it->second.root}];
    ++count.first;
    count.second += below;
  }
  for (const auto& [pair, count] : under) {
    const auto group = static_cast<double>(size[static_cast<std::size_t>(pair.first)]);
    const auto building = static_cast<double>(size[static_cast<std::size_t>(pair.second)]);
    const bool small = group <= s.enclosure_size_ratio * building;
    const bool below = static_cast<double>(count.second) >= s.footprint_share * group;
    if (static_cast<double>(count.first) >= s.footprint_share * group && (small || below))
      groups.unite(pair.first, pair.second);
  }
}

std::vector<std::int8_t>
roofSides(const Contacts& c, const std::vector<SegmentKind>& kind, const AssemblySettings& s,
          const Groups& groups)
{
  const std::size_t n = kind.size();
  Groups g = groups;  // touching roofs join only in attachUnderRoofs
  std::vector<std::size_t> size(n, 0), points(n, 0), under(n, 0);
  for (std::size_t p = 0; p < c.labels.size(); ++p)
    if (c.labels[p] >= 0)
      ++size[static_cast<std::size_t>(g.find(c.labels[p]))];
  const double cell = std::sqrt(c.max_sq);
  const int reach = static_cast<int>(std::ceil(s.footprint_margin / cell));
  std::vector<char> building(n, 0);
  const auto footprint = buildingFootprints(c, kind, size, cell, reach, s.min_links, g, building);
  for (std::size_t p = 0; p < c.labels.size(); ++p) {
    if (c.labels[p] < 0)
      continue;
    const auto seg = static_cast<std::size_t>(c.labels[p]);
    ++points[seg];
    const auto it = footprint.find(cellKey(c.points[p], cell));
    under[seg] += it != footprint.end() && !it->second.margin && it->second.root != g.find(c.labels[p]) &&
                  c.points[p].z() < it->second.top;
  }
  std::vector<std::int8_t> side(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (kind[i] == SegmentKind::Ground || points[i] == 0)
      continue;
    const double share = static_cast<double>(under[i]) / static_cast<double>(points[i]);
    side[i] = share >= s.footprint_share ? 1 : 1.0 - share >= s.footprint_share ? -1 : 0;
  }
  return side;
}

}  // namespace detail
}  // namespace segmentation
}  // namespace pcl_ls3d
