/// \file object_assembly.cpp
/// \brief The joining of touching segments into objects.

#include <pcl_ls3d/segmentation/object_assembly.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

namespace pcl_ls3d {
namespace segmentation {
namespace {

bool
structural(SegmentKind k)
{
  return k == SegmentKind::Solid || k == SegmentKind::Wall;
}

/// May two touching segments (a, b) with \a links links join symmetrically? Linear segments
/// never do: two spans of a wire meet end to end at their tower, and joining them would make
/// one object of two; attachLines() places lines that run along a structure.
bool
joinable(int a, int b, std::size_t links, const std::vector<SegmentKind>& kind,
         const std::vector<char>& on_terrain, const AssemblySettings& s)
{
  if (links < s.min_links || on_terrain[static_cast<std::size_t>(a)] ||
      on_terrain[static_cast<std::size_t>(b)])
    return false;
  const SegmentKind ka = kind[static_cast<std::size_t>(a)], kb = kind[static_cast<std::size_t>(b)];
  if (ka == SegmentKind::Ground || kb == SegmentKind::Ground)
    return ka == kb;
  if (structural(ka) && structural(kb))
    return true;
  if (ka == SegmentKind::Rough && kb == SegmentKind::Rough)
    return true;
  return false;
}

/// The point-level contacts the attachments look at.
struct Contacts
{
  const std::vector<Eigen::Vector3f>& points;
  const std::vector<int>& graph;
  int graph_k;
  const std::vector<int>& labels;
  double max_sq;
};

/// Union-find over segments.
class Groups
{
public:
  explicit Groups(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int s)
  {
    while (parent_[static_cast<std::size_t>(s)] != s) {
      const int up = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(s)])];
      parent_[static_cast<std::size_t>(s)] = up;
      s = up;
    }
    return s;
  }
  void unite(int a, int b)
  {
    const int ra = find(a), rb = find(b);
    if (ra != rb)
      parent_[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
  }

private:
  std::vector<int> parent_;
};

/// A piece detached from the ground (detachRaisedPoints) joins the one non-ground group it has
/// most links with (the hedge above its foot, the wall above its foot), or stays alone (low
/// vegetation in a lawn). It never joins two groups: a strip of low points along a wall must not
/// bridge the wall and the hedge beside it.
void
attachTerrainPieces(const std::vector<SegmentLink>& adjacency, const std::vector<SegmentKind>& kind,
                    const std::vector<char>& on_terrain, const AssemblySettings& s, Groups& groups)
{
  std::vector<int> target(kind.size(), -1);
  std::vector<std::size_t> best(kind.size(), 0);
  for (const SegmentLink& l : adjacency)
    for (const auto& [piece, other] : {std::pair{l.a, l.b}, std::pair{l.b, l.a}}) {
      const auto p = static_cast<std::size_t>(piece), o = static_cast<std::size_t>(other);
      if (on_terrain[p] && !on_terrain[o] && kind[o] != SegmentKind::Ground && l.links > best[p]) {
        best[p] = l.links;
        target[p] = other;
      }
    }
  for (std::size_t p = 0; p < kind.size(); ++p)
    if (target[p] >= 0 && best[p] >= s.min_links)
      groups.unite(static_cast<int>(p), target[p]);
}

std::size_t
countRoots(Groups& groups, std::size_t n)
{
  std::size_t roots = 0;
  for (std::size_t i = 0; i < n; ++i)
    roots += groups.find(static_cast<int>(i)) == static_cast<int>(i);
  return roots;
}

/// Places each linear segment (lines never join each other) into the one non-linear,
/// non-ground group that most of its points touch, if at least edge_share of its points have
/// a neighbour there (an edge line along a roof, a branch in a crown). A wire span touches
/// its tower only with the few points at its end and stays alone; a line between a roof and
/// a tree joins one of them, never bridging the two.
void
attachLines(const Contacts& c, const std::vector<SegmentShape>& shapes,
            const std::vector<SegmentKind>& kind, const AssemblySettings& s, Groups& groups)
{
  std::map<std::pair<int, int>, std::size_t> touching;  // (line, other root) -> line points
  std::vector<int> seen;
  for (std::size_t p = 0; p < c.labels.size(); ++p) {
    const int line = c.labels[p];
    if (line < 0 || kind[static_cast<std::size_t>(line)] != SegmentKind::Linear)
      continue;
    seen.clear();
    for (int g = 0; g < c.graph_k; ++g) {
      const int q = c.graph[p * static_cast<std::size_t>(c.graph_k) + static_cast<std::size_t>(g)];
      if (q < 0 || c.labels[static_cast<std::size_t>(q)] < 0 ||
          (c.points[p] - c.points[static_cast<std::size_t>(q)]).squaredNorm() > c.max_sq)
        continue;
      const int other = c.labels[static_cast<std::size_t>(q)];
      const SegmentKind ko = kind[static_cast<std::size_t>(other)];
      if (ko == SegmentKind::Linear || ko == SegmentKind::Ground)
        continue;
      const int root = groups.find(other);
      if (std::find(seen.begin(), seen.end(), root) == seen.end()) {
        seen.push_back(root);
        ++touching[{line, root}];
      }
    }
  }
  std::vector<int> target(shapes.size(), -1);
  std::vector<std::size_t> best(shapes.size(), 0);
  for (const auto& [pair, count] : touching)
    if (count > best[static_cast<std::size_t>(pair.first)]) {
      best[static_cast<std::size_t>(pair.first)] = count;
      target[static_cast<std::size_t>(pair.first)] = pair.second;
    }
  for (std::size_t line = 0; line < shapes.size(); ++line)
    if (target[line] >= 0 &&
        static_cast<double>(best[line]) >= s.edge_share * static_cast<double>(shapes[line].n))
      groups.unite(static_cast<int>(line), target[line]);
}

/// A non-linear, non-ground group whose contacts go (enclosure_share of its links) to one
/// building group at least 1/enclosure_size_ratio times larger sits on it and joins it: a
/// chimney, dormer or roof window. A car on the ground or a tree beside a house has other
/// contacts; the size ratio keeps a crown that only touches a roof out of the building. A group
/// holding a piece detached from the ground stands on the terrain and never sits on a roof;
/// links to such pieces are contacts with the terrain, whatever group the piece has joined.
void
attachEnclosed(const std::vector<SegmentLink>& adjacency, const std::vector<SegmentShape>& shapes,
               const std::vector<SegmentKind>& kind, const std::vector<char>& on_terrain,
               const AssemblySettings& s, Groups& groups)
{
  const std::size_t n = shapes.size();
  std::vector<std::size_t> size(n, 0), total(n, 0), rough(n, 0);
  std::vector<char> eligible(n, 1);  // roots whose members are neither ground nor linear
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = static_cast<std::size_t>(groups.find(static_cast<int>(i)));
    size[r] += shapes[i].n;
    rough[r] += kind[i] == SegmentKind::Rough ? shapes[i].n : 0;
    if (kind[i] == SegmentKind::Ground || kind[i] == SegmentKind::Linear || on_terrain[i])
      eligible[r] = 0;
  }
  // A rough group (vegetation-like: a crown, or a chimney's scattered returns) sits on a
  // building only if it lies on its roof in plan (attachUnderRoofs); contact alone does not
  // make a crown that leans over a roof part of it.
  for (std::size_t r = 0; r < n; ++r)
    if (2 * rough[r] > size[r])
      eligible[r] = 0;
  std::map<std::pair<int, int>, std::size_t> links;  // (root, other root) -> links
  for (const SegmentLink& l : adjacency) {
    const int ra = groups.find(l.a), rb = groups.find(l.b);
    if (ra == rb)
      continue;
    total[static_cast<std::size_t>(ra)] += l.links;
    total[static_cast<std::size_t>(rb)] += l.links;
    if (on_terrain[static_cast<std::size_t>(l.a)] || on_terrain[static_cast<std::size_t>(l.b)])
      continue;
    links[{ra, rb}] += l.links;
    links[{rb, ra}] += l.links;
  }
  std::vector<int> target(n, -1);
  std::vector<std::size_t> best(n, 0);
  for (const auto& [pair, count] : links) {
    const auto from = static_cast<std::size_t>(pair.first), to = static_cast<std::size_t>(pair.second);
    // Only a building takes what sits on it: a roof piece enclosed by a crown stays a roof
    // piece. A root's kind stands for its group (joins keep kind families apart).
    if (eligible[from] && structural(kind[to]) && size[to] > 20 * size[from] && count > best[from]) {
      best[from] = count;
      target[from] = pair.second;
    }
  }
  for (std::size_t r = 0; r < n; ++r) {
    if (target[r] >= 0 && best[r] >= s.min_links &&
        static_cast<double>(best[r]) >= s.enclosure_share * static_cast<double>(total[r]))
      groups.unite(static_cast<int>(r), target[r]);
  }
}

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
joinTouchingRoofs(const std::unordered_map<std::int64_t, int>& own, int reach,
                  std::size_t min_contacts, Groups& groups)
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
};

/// Per horizontal cell: the building group (most of its points in roof or wall segments) with
/// most points in it, spread over the cells within \a reach of it (a cell keeps its own), and
/// that building's highest structural point in the cell (spread cells: in the cells they
/// spread from).
std::unordered_map<std::int64_t, RoofCell>
buildingFootprints(const Contacts& c, const std::vector<SegmentKind>& kind,
                   const std::vector<std::size_t>& size, double cell, int reach,
                   std::size_t min_contacts, Groups& groups)
{
  std::vector<std::size_t> structural_points(size.size(), 0);
  for (std::size_t p = 0; p < c.labels.size(); ++p)
    if (c.labels[p] >= 0 && structural(kind[static_cast<std::size_t>(c.labels[p])]))
      ++structural_points[static_cast<std::size_t>(groups.find(c.labels[p]))];
  std::unordered_map<std::int64_t, std::map<int, std::size_t>> count;
  for (std::size_t p = 0; p < c.labels.size(); ++p) {
    if (c.labels[p] < 0 || !structural(kind[static_cast<std::size_t>(c.labels[p])]))
      continue;
    const auto root = static_cast<std::size_t>(groups.find(c.labels[p]));
    if (2 * structural_points[root] > size[root])
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
        const auto [it, fresh] = spread.emplace(to, rc);
        if (!fresh && it->second.root == rc.root)
          it->second.top = std::max(it->second.top, rc.top);
      }
  for (const auto& [key, rc] : own)
    spread[key] = rc;
  return spread;
}

/// A non-ground group whose points lie (footprint_share of them) on or under one building's
/// roof in plan, within footprint_margin of it, joins it if it is at most
/// enclosure_size_ratio of that building (chimneys and roof units: dense blobs whose k-NN links
/// stay inside themselves) or if those points also lie below the building's roof or walls in
/// their cell, whatever its size: a facade with balconies under the eaves of a roof that the
/// tile edge cut to a strip. A tree beside a house has most of its crown outside the
/// footprint; a crown over a roof lies above it and stays bound by the size ratio.
void
attachUnderRoofs(const Contacts& c, const std::vector<SegmentKind>& kind,
                 const AssemblySettings& s, Groups& groups)
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
  const auto footprint = buildingFootprints(c, kind, size, cell, reach, s.min_links, groups);
  std::fill(size.begin(), size.end(), 0);  // touching roofs may have joined
  for (std::size_t p = 0; p < c.labels.size(); ++p)
    if (c.labels[p] >= 0)
      ++size[static_cast<std::size_t>(groups.find(c.labels[p]))];
  // (group, building) -> points in the footprint, and those of them below the roof
  std::map<std::pair<int, int>, std::pair<std::size_t, std::size_t>> under;
  for (std::size_t p = 0; p < c.labels.size(); ++p) {
    if (c.labels[p] < 0)
      continue;
    const int root = groups.find(c.labels[p]);
    const auto it = footprint.find(cellKey(c.points[p], cell));
    if (!eligible[static_cast<std::size_t>(root)] || it == footprint.end() || it->second.root == root)
      continue;
    auto& count = under[{root, it->second.root}];
    ++count.first;
    count.second += c.points[p].z() < it->second.top;
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

/// Points of a ground segment that the ground filter rejects (higher above the opened terrain
/// than its noise allowance) are not ground: the foot of a hedge, low vegetation, a wall's foot
/// that the planar growth carried along the terrain. They leave the segment as new segments, one
/// per connected component of such points (k-NN links no longer than \a max_length), and are
/// assembled like any other segment. \a labels stays dense.
/// \return points detached
std::size_t
detachRaisedPoints(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& graph,
                   int graph_k, const std::vector<char>& ground,
                   const std::vector<SegmentKind>& kind, double max_length,
                   std::vector<int>& labels, std::vector<int>& origin)
{
  origin.clear();
  const double max_sq = max_length * max_length;
  const auto raised = [&](std::size_t p) {
    return labels[p] >= 0 && !ground[p] &&
           kind[static_cast<std::size_t>(labels[p])] == SegmentKind::Ground;
  };
  int next = static_cast<int>(kind.size());
  std::size_t detached = 0;
  std::vector<int> stack;
  std::vector<int> fresh(labels.size(), -1);
  for (std::size_t p = 0; p < labels.size(); ++p) {
    if (!raised(p) || fresh[p] >= 0)
      continue;
    const int from = labels[p];
    origin.push_back(from);
    fresh[p] = next;
    stack.assign(1, static_cast<int>(p));
    while (!stack.empty()) {
      const auto i = static_cast<std::size_t>(stack.back());
      stack.pop_back();
      for (int g = 0; g < graph_k; ++g) {
        const int q = graph[i * static_cast<std::size_t>(graph_k) + static_cast<std::size_t>(g)];
        if (q < 0 || fresh[static_cast<std::size_t>(q)] >= 0 || !raised(static_cast<std::size_t>(q)) ||
            labels[static_cast<std::size_t>(q)] != from ||
            (points[i] - points[static_cast<std::size_t>(q)]).squaredNorm() > max_sq)
          continue;
        fresh[static_cast<std::size_t>(q)] = next;
        stack.push_back(q);
      }
    }
    ++next;
  }
  for (std::size_t p = 0; p < labels.size(); ++p)
    if (fresh[p] >= 0) {
      labels[p] = fresh[p];
      ++detached;
    }
  return detached;
}

/// A detached piece as smooth as a roof or the terrain (kind Solid: not rough, not a wall, not
/// a line) is terrain the filter misjudged (a steep slope, an embankment, a tile edge) and goes
/// back to its ground segment; rough pieces (vegetation) and walls stay detached. Pieces are
/// the labels from \a first on, \a origin their ground segments; labels stay dense.
/// \return points that stay detached
std::size_t
restoreTerrainPieces(const std::vector<SegmentKind>& kind, std::size_t first,
                     const std::vector<int>& origin, std::vector<int>& labels)
{
  std::vector<int> to(kind.size(), -1);
  int next = static_cast<int>(first);
  for (std::size_t s = first; s < kind.size(); ++s)
    to[s] = kind[s] == SegmentKind::Solid ? origin[s - first] : next++;
  std::size_t kept = 0;
  for (int& l : labels)
    if (l >= static_cast<int>(first)) {
      l = to[static_cast<std::size_t>(l)];
      kept += l >= static_cast<int>(first);
    }
  return kept;
}

}  // namespace

AssemblyReport
assembleObjects(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& graph,
                int graph_k, const std::vector<float>& residuals, const std::vector<char>& ground,
                const AssemblySettings& settings, std::vector<int>& labels)
{
  AssemblyReport rep;
  if (points.size() != labels.size() || ground.size() != labels.size() ||
      residuals.size() != labels.size())
    return rep;
  rep.ground_residual = groundResidual(residuals, ground);
  const auto kindsOf = [&](const std::vector<SegmentShape>& shapes) {
    std::vector<SegmentKind> kind(shapes.size());
    for (std::size_t s = 0; s < shapes.size(); ++s)
      kind[s] = kindOf(shapes[s], rep.ground_residual, settings.kinds);
    return kind;
  };
  auto shapes = segmentShapes(points, labels, residuals, ground);
  rep.segments_before = shapes.size();
  std::vector<SegmentKind> kind = kindsOf(shapes);
  if (settings.detach_raised_points) {
    std::vector<int> origin;
    rep.detached_points = detachRaisedPoints(points, graph, graph_k, ground, kind,
                                             settings.max_link_length, labels, origin);
    if (rep.detached_points > 0) {
      const auto pieces = segmentShapes(points, labels, residuals, ground);
      rep.detached_points = restoreTerrainPieces(kindsOf(pieces), rep.segments_before, origin, labels);
      shapes = segmentShapes(points, labels, residuals, ground);
      kind = kindsOf(shapes);
    }
  }
  for (const SegmentKind k : kind)
    ++rep.kind_count[static_cast<int>(k)];

  // Segments detached from the ground stand on the terrain: neither they nor a group holding
  // them sits on a roof (a hedge and its foot, a crown whose trunk reaches the ground).
  std::vector<char> on_terrain(shapes.size(), 0);
  for (std::size_t i = rep.segments_before; i < shapes.size(); ++i)
    on_terrain[i] = 1;
  Groups groups(shapes.size());
  const std::vector<SegmentLink> adjacency = segmentAdjacency(points, graph, graph_k, labels, settings.max_link_length);
  const auto isRough = [&kind](int s) { return kind[static_cast<std::size_t>(s)] == SegmentKind::Rough; };
  for (const SegmentLink& l : adjacency)
    if (!(isRough(l.a) && isRough(l.b)) && joinable(l.a, l.b, l.links, kind, on_terrain, settings))
      groups.unite(l.a, l.b);
  // Crowns join crowns only through links as short as the volumetric growth steps: two trees
  // whose crowns come within the (longer) roof-growth radius of each other stay two trees.
  const double rough_length = settings.rough_link_length > 0.0
                                  ? std::min(settings.rough_link_length, settings.max_link_length)
                                  : settings.max_link_length;
  for (const SegmentLink& l : segmentAdjacency(points, graph, graph_k, labels, rough_length))
    if (isRough(l.a) && isRough(l.b) && joinable(l.a, l.b, l.links, kind, on_terrain, settings))
      groups.unite(l.a, l.b);
  attachTerrainPieces(adjacency, kind, on_terrain, settings, groups);
  const Contacts contacts{points, graph, graph_k, labels,
                          settings.max_link_length * settings.max_link_length};
  // Attachments see groups, and each one can complete another (a roof takes its chimney, then
  // the edge line along both): repeat until nothing joins.
  for (std::size_t before = 0, after = 1; before != after;) {
    before = countRoots(groups, shapes.size());
    attachLines(contacts, shapes, kind, settings, groups);
    attachEnclosed(adjacency, shapes, kind, on_terrain, settings, groups);
    attachUnderRoofs(contacts, kind, settings, groups);
    after = countRoots(groups, shapes.size());
  }
  std::vector<int> dense(shapes.size(), -1);
  int next = 0;
  for (int& l : labels) {
    if (l < 0)
      continue;
    const int root = groups.find(l);
    if (dense[static_cast<std::size_t>(root)] < 0)
      dense[static_cast<std::size_t>(root)] = next++;
    l = dense[static_cast<std::size_t>(root)];
  }
  rep.objects = static_cast<std::size_t>(next);
  return rep;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
