/// \file object_assembly.cpp
/// \brief The joining of touching segments into objects.

#include <pcl_ls3d/segmentation/object_assembly.h>

#include <pcl_ls3d/segmentation/ground_filter.h>

#include "assembly_groups.h"
#include "roof_footprints.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace pcl_ls3d {
namespace segmentation {
namespace {

using detail::Contacts;
using detail::Groups;
using detail::structural;

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
attachLines(const Contacts& c, const std::vector<SegmentShape>& shapes, const std::vector<SegmentKind>& kind,
            const AssemblySettings& s, Groups& groups)
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

/// Raised points of a ground segment (\a raised_point, from raisedPoints(): rejected by the
/// ground filter, or clearly above the terrain plane around them) are not ground: the foot of a
/// hedge, low vegetation, grass, a wall's foot that the planar growth carried along the
/// terrain. They leave the segment as new segments, one
/// per connected component of such points (k-NN links no longer than \a max_length), and are
/// assembled like any other segment. \a labels stays dense.
/// \return points detached
std::size_t
detachRaisedPoints(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& graph, int graph_k,
                   const std::vector<char>& raised_point, const std::vector<SegmentKind>& kind,
                   double max_length, std::vector<int>& labels, std::vector<int>& origin)
{
  origin.clear();
  const double max_sq = max_length * max_length;
  const auto raised = [&](std::size_t p) { return raised_point[p] != 0; };  // ground segments only
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

/// Points of ground segments that stand above the terrain: rejected by the ground filter, or
/// kept by it but higher than \a limit above the terrain plane of the ground points around
/// them (heightAboveTerrain with \a half_width; limit ≤ 0: the filter alone).
std::vector<char>
raisedPoints(const std::vector<Eigen::Vector3f>& points, const std::vector<char>& ground,
             const std::vector<SegmentKind>& kind, const std::vector<int>& labels, double limit,
             double half_width)
{
  std::vector<char> raised(points.size(), 0), kept_on_ground(points.size(), 0);
  for (std::size_t p = 0; p < points.size(); ++p)
    if (labels[p] >= 0 && kind[static_cast<std::size_t>(labels[p])] == SegmentKind::Ground) {
      raised[p] = !ground[p];
      kept_on_ground[p] = ground[p] && limit > 0.0;
    }
  if (!(limit > 0.0))  // also a NaN multiple or residual
    return raised;
  const std::vector<float> height = heightAboveTerrain(points, ground, kept_on_ground, half_width);
  for (std::size_t p = 0; p < points.size(); ++p)
    raised[p] = raised[p] || (kept_on_ground[p] && height[p] > limit);  // NaN: not raised
  return raised;
}

/// A detached piece as smooth as a roof or the terrain (kind Solid: not rough, not a wall, not
/// a line) is terrain the filter misjudged (a steep slope, an embankment, a tile edge) and goes
/// back to its ground segment; rough pieces (vegetation) and walls stay detached. Pieces are
/// the labels from \a first on, \a origin their ground segments; labels stay dense.
/// \return points that stay detached
std::size_t
restoreTerrainPieces(const std::vector<SegmentKind>& kind, std::size_t first, const std::vector<int>& origin,
                     std::vector<int>& labels)
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

/// Kinds of the segments; pieces detached from the ground are judged by their points too: a
/// flat patch of low vegetation, rough in its points, is vegetation standing on the terrain,
/// not a roof.
std::vector<SegmentKind>
segmentKinds(const std::vector<SegmentShape>& shapes, std::size_t first_piece, double ground_residual,
             const KindSettings& settings)
{
  std::vector<SegmentKind> kind(shapes.size());
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    kind[s] = kindOf(shapes[s], ground_residual, settings);
    if (s >= first_piece && kind[s] != SegmentKind::Linear &&
        hasRoughPoints(shapes[s], ground_residual, settings))
      kind[s] = SegmentKind::Rough;
  }
  return kind;
}

/// Stage 1: raised points leave their ground segments (detachRaisedPoints), pieces as smooth as
/// terrain go back (restoreTerrainPieces). Returns the segments' shapes and kinds afterwards.
std::vector<SegmentShape>
detachStage(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& graph, int graph_k,
            const std::vector<float>& residuals, const std::vector<char>& ground,
            const AssemblySettings& settings, std::vector<int>& labels, std::vector<SegmentKind>& kind,
            AssemblyReport& rep)
{
  std::vector<SegmentShape> shapes = segmentShapes(points, labels, residuals, ground);
  rep.segments_before = shapes.size();
  kind = segmentKinds(shapes, shapes.size(), rep.ground_residual, settings.kinds);
  if (!settings.detach_raised_points)
    return shapes;
  std::vector<int> origin;
  const std::vector<char> raised =
      raisedPoints(points, ground, kind, labels, settings.raised_noise_multiple * rep.ground_residual,
                   terrainWindowHalfWidth(settings));
  rep.detached_points =
      detachRaisedPoints(points, graph, graph_k, raised, kind, settings.max_link_length, labels, origin);
  if (rep.detached_points == 0)
    return shapes;
  const auto pieces = segmentShapes(points, labels, residuals, ground);
  rep.detached_points =
      restoreTerrainPieces(segmentKinds(pieces, rep.segments_before, rep.ground_residual, settings.kinds),
                           rep.segments_before, origin, labels);
  shapes = segmentShapes(points, labels, residuals, ground);
  kind = segmentKinds(shapes, rep.segments_before, rep.ground_residual, settings.kinds);
  return shapes;
}

/// Stage 2: touching segments whose kinds belong together join; crowns only through links as
/// short as the volumetric growth steps (two trees whose crowns come within the longer
/// roof-growth radius stay two trees), and never what hangs under a roof with what lies outside
/// it (a balcony row under the eaves, the hedge at the facade's foot). Pieces detached from the
/// ground then take their one neighbour group.
void
joinTouching(const Contacts& contacts, const std::vector<SegmentLink>& adjacency,
             const std::vector<SegmentKind>& kind, const std::vector<char>& on_terrain,
             const AssemblySettings& settings, Groups& groups)
{
  const auto isRough = [&kind](int s) { return kind[static_cast<std::size_t>(s)] == SegmentKind::Rough; };
  for (const SegmentLink& l : adjacency)
    if (!(isRough(l.a) && isRough(l.b)) && joinable(l.a, l.b, l.links, kind, on_terrain, settings))
      groups.unite(l.a, l.b);
  const double rough_length = settings.rough_link_length > 0.0
                                  ? std::min(settings.rough_link_length, settings.max_link_length)
                                  : settings.max_link_length;
  const std::vector<std::int8_t> side = detail::roofSides(contacts, kind, settings, groups);
  for (const SegmentLink& l :
       segmentAdjacency(contacts.points, contacts.graph, contacts.graph_k, contacts.labels, rough_length))
    if (isRough(l.a) && isRough(l.b) &&
        side[static_cast<std::size_t>(l.a)] * side[static_cast<std::size_t>(l.b)] >= 0 &&
        joinable(l.a, l.b, l.links, kind, on_terrain, settings))
      groups.unite(l.a, l.b);
  attachTerrainPieces(adjacency, kind, on_terrain, settings, groups);
}

/// Stage 3: attachments see groups, and each one can complete another (a roof takes its
/// chimney, then the edge line along both): repeated until nothing joins.
void
attachUntilStable(const Contacts& contacts, const std::vector<SegmentLink>& adjacency,
                  const std::vector<SegmentShape>& shapes, const std::vector<SegmentKind>& kind,
                  const std::vector<char>& on_terrain, const AssemblySettings& settings, Groups& groups)
{
  std::vector<char> building(shapes.size(), 0);  // per segment: in a building group
  for (std::size_t before = 0, after = 1; before != after;) {
    before = countRoots(groups, shapes.size());
    attachLines(contacts, shapes, kind, settings, groups);
    attachEnclosed(adjacency, shapes, kind, on_terrain, settings, groups);
    detail::attachUnderRoofs(contacts, kind, settings, groups, building);
    after = countRoots(groups, shapes.size());
  }
}

/// Labels become dense object ids, one per group; returns the number of objects.
std::size_t
relabelByGroup(Groups& groups, std::size_t segments, std::vector<int>& labels)
{
  std::vector<int> dense(segments, -1);
  int next = 0;
  for (int& l : labels) {
    if (l < 0)
      continue;
    const int root = groups.find(l);
    if (dense[static_cast<std::size_t>(root)] < 0)
      dense[static_cast<std::size_t>(root)] = next++;
    l = dense[static_cast<std::size_t>(root)];
  }
  return static_cast<std::size_t>(next);
}

}  // namespace

std::function<bool(int, int)>
absorptionContact(const std::vector<Eigen::Vector3f>& points, const std::vector<SegmentKind>& point_kind,
                  double max_link_length)
{
  if (points.size() != point_kind.size())
    return [](int, int) { return false; };
  const double max_sq = max_link_length * max_link_length;
  return [&points, &point_kind, max_sq](int p, int q) {
    const auto a = static_cast<std::size_t>(p), b = static_cast<std::size_t>(q);
    if ((points[a] - points[b]).squaredNorm() > max_sq)
      return false;
    return !(point_kind[a] == SegmentKind::Rough && point_kind[b] == SegmentKind::Ground);
  };
}

AssemblyReport
assembleObjects(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& graph, int graph_k,
                const std::vector<float>& residuals, const std::vector<char>& ground,
                const AssemblySettings& settings, std::vector<int>& labels)
{
  AssemblyReport rep;
  if (points.size() != labels.size() || ground.size() != labels.size() || residuals.size() != labels.size())
    return rep;
  rep.ground_residual = groundResidual(residuals, ground);
  std::vector<SegmentKind> kind;
  const std::vector<SegmentShape> shapes =
      detachStage(points, graph, graph_k, residuals, ground, settings, labels, kind, rep);
  for (const SegmentKind k : kind)
    ++rep.kind_count[static_cast<int>(k)];
  rep.point_kind.assign(labels.size(), SegmentKind::Solid);
  for (std::size_t p = 0; p < labels.size(); ++p)
    if (labels[p] >= 0)
      rep.point_kind[p] = kind[static_cast<std::size_t>(labels[p])];

  // Segments detached from the ground stand on the terrain: neither they nor a group holding
  // them sits on a roof (a hedge and its foot, a crown whose trunk reaches the ground).
  std::vector<char> on_terrain(shapes.size(), 0);
  for (std::size_t i = rep.segments_before; i < shapes.size(); ++i)
    on_terrain[i] = 1;
  Groups groups(shapes.size());
  const std::vector<SegmentLink> adjacency =
      segmentAdjacency(points, graph, graph_k, labels, settings.max_link_length);
  const Contacts contacts{points, graph, graph_k, labels,
                          settings.max_link_length * settings.max_link_length};
  joinTouching(contacts, adjacency, kind, on_terrain, settings, groups);
  attachUntilStable(contacts, adjacency, shapes, kind, on_terrain, settings, groups);
  rep.objects = relabelByGroup(groups, shapes.size(), labels);
  return rep;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
