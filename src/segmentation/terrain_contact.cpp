/// \file terrain_contact.cpp
/// \brief Vegetation and car points on the terrain join the ground object beside them
///        (terrain_contact.h).

#include <pcl_ls3d/segmentation/terrain_contact.h>

#include <pcl_ls3d/segmentation/ground_filter.h>

#include <numeric>
#include <utility>

namespace pcl_ls3d {
namespace segmentation {
namespace {

/// Objects whose rough segments take the ground at their foot: crowns and hedges, and parked
/// cars grown as rough objects (named car by their returns).
bool
holdsGroundAtItsFoot(ObjectClass c)
{
  return c == ObjectClass::Vegetation || c == ObjectClass::Car;
}

/// Vegetation and car points the ground filter keeps, no higher than \a limit above the terrain
/// plane (NaN: the terrain is unknown there).
std::vector<std::size_t>
pointsOnTerrain(const std::vector<Eigen::Vector3f>& points, const std::vector<char>& ground,
                const std::vector<ObjectClass>& object_class, double limit, double half_width,
                const std::vector<int>& labels)
{
  std::vector<char> wanted(points.size(), 0);
  for (std::size_t p = 0; p < points.size(); ++p)
    wanted[p] = ground[p] && holdsGroundAtItsFoot(classOf(labels[p], object_class));
  const std::vector<float> height = heightAboveTerrain(points, ground, wanted, half_width);
  std::vector<std::size_t> out;
  for (std::size_t p = 0; p < points.size(); ++p)
    if (wanted[p] && height[p] <= limit)
      out.push_back(p);
  return out;
}

/// The ground object sharing the most of point \a p's k-NN links (ties: the smaller id), −1
/// if none. At most k objects: a flat list, no map.
int
mostLinkedGround(std::size_t p, const std::vector<int>& graph, std::size_t k,
                 const std::vector<ObjectClass>& object_class, const std::vector<int>& labels)
{
  std::vector<std::pair<int, int>> links;  // (object, count)
  for (std::size_t c = 0; c < k; ++c) {
    const int q = graph[p * k + c];
    if (q < 0)
      continue;
    const int object = labels[static_cast<std::size_t>(q)];
    if (classOf(object, object_class) != ObjectClass::Ground)
      continue;
    auto it = links.begin();
    while (it != links.end() && it->first != object)
      ++it;
    if (it == links.end())
      links.emplace_back(object, 1);
    else
      ++it->second;
  }
  int best = -1, most = 0;
  for (const auto& [object, n] : links)
    if (n > most || (n == most && object < best)) {
      best = object;
      most = n;
    }
  return best;
}

/// Per candidate (index into \a on_terrain): the candidates that have it among their k nearest
/// neighbours, so that a round re-checks only the candidates next to a point that just moved.
std::vector<std::vector<std::size_t>>
candidatesLinkingTo(const std::vector<std::size_t>& on_terrain, std::size_t n_points,
                    const std::vector<int>& graph, std::size_t k)
{
  std::vector<int> slot(n_points, -1);
  for (std::size_t i = 0; i < on_terrain.size(); ++i)
    slot[on_terrain[i]] = static_cast<int>(i);
  std::vector<std::vector<std::size_t>> linked_from(on_terrain.size());
  for (std::size_t i = 0; i < on_terrain.size(); ++i)
    for (std::size_t c = 0; c < k; ++c) {
      const int q = graph[on_terrain[i] * k + c];
      if (q >= 0 && slot[static_cast<std::size_t>(q)] >= 0)
        linked_from[static_cast<std::size_t>(slot[static_cast<std::size_t>(q)])].push_back(i);
    }
  return linked_from;
}

}  // namespace

std::size_t
returnTerrainPoints(const std::vector<Eigen::Vector3f>& points, const std::vector<char>& ground,
                    const std::vector<int>& graph, int graph_k, const std::vector<ObjectClass>& object_class,
                    double limit, double half_width, std::vector<int>& labels)
{
  const std::size_t n = points.size();
  const std::size_t k = graph_k > 0 ? static_cast<std::size_t>(graph_k) : 0;
  if (ground.size() != n || labels.size() != n || graph.size() != n * k || k == 0 || !(limit > 0.0))
    return 0;
  const std::vector<std::size_t> on_terrain =
      pointsOnTerrain(points, ground, object_class, limit, half_width, labels);
  const std::vector<std::vector<std::size_t>> linked_from = candidatesLinkingTo(on_terrain, n, graph, k);
  // Rounds from the lawn inwards; a round decides on the labels as it found them.
  std::vector<std::size_t> check(on_terrain.size());
  std::iota(check.begin(), check.end(), std::size_t{0});
  std::vector<std::pair<std::size_t, int>> moves;
  std::vector<char> queued(on_terrain.size(), 0);
  std::size_t moved = 0;
  while (!check.empty()) {
    moves.clear();
    for (const std::size_t i : check) {
      const std::size_t p = on_terrain[i];
      if (!holdsGroundAtItsFoot(classOf(labels[p], object_class)))
        continue;
      const int to = mostLinkedGround(p, graph, k, object_class, labels);
      if (to >= 0)
        moves.emplace_back(i, to);
    }
    check.clear();
    for (const auto& [i, to] : moves)
      labels[on_terrain[i]] = to;
    for (const auto& [i, to] : moves)
      for (const std::size_t j : linked_from[i])
        if (!queued[j] && holdsGroundAtItsFoot(classOf(labels[on_terrain[j]], object_class))) {
          queued[j] = 1;
          check.push_back(j);
        }
    for (const std::size_t j : check)
      queued[j] = 0;
    moved += moves.size();
  }
  return moved;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
