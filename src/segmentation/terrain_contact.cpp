/// \file terrain_contact.cpp
/// \brief Vegetation points on the terrain join the ground object beside them
///        (terrain_contact.h).

#include <pcl_ls3d/segmentation/terrain_contact.h>

#include <pcl_ls3d/segmentation/ground_filter.h>

#include <map>

namespace pcl_ls3d {
namespace segmentation {
namespace {

bool
isOfClass(int label, const std::vector<ObjectClass>& object_class, ObjectClass c)
{
  return label >= 0 && static_cast<std::size_t>(label) < object_class.size() &&
         object_class[static_cast<std::size_t>(label)] == c;
}

/// The ground object sharing the most of point \a p's k-NN links (ties: the smaller id), −1 if
/// none.
int
mostLinkedGround(std::size_t p, const std::vector<int>& graph, std::size_t k,
                 const std::vector<ObjectClass>& object_class, const std::vector<int>& labels)
{
  std::map<int, int> links;
  for (std::size_t c = 0; c < k; ++c) {
    const int q = graph[p * k + c];
    if (q >= 0 && isOfClass(labels[static_cast<std::size_t>(q)], object_class, ObjectClass::Ground))
      ++links[labels[static_cast<std::size_t>(q)]];
  }
  int best = -1, most = 0;
  for (const auto& [object, n] : links)
    if (n > most) {
      best = object;
      most = n;
    }
  return best;
}

}  // namespace

std::size_t
returnTerrainPoints(const std::vector<Eigen::Vector3f>& points, const std::vector<char>& ground,
                    const std::vector<int>& graph, int graph_k,
                    const std::vector<ObjectClass>& object_class, double limit,
                    double half_width, std::vector<int>& labels)
{
  const std::size_t n = points.size();
  const std::size_t k = graph_k > 0 ? static_cast<std::size_t>(graph_k) : 0;
  if (ground.size() != n || labels.size() != n || graph.size() != n * k || k == 0 ||
      !(limit > 0.0))
    return 0;
  std::vector<char> wanted(n, 0);
  for (std::size_t p = 0; p < n; ++p)
    wanted[p] = ground[p] && isOfClass(labels[p], object_class, ObjectClass::Vegetation);
  const std::vector<float> height = heightAboveTerrain(points, ground, wanted, half_width);
  std::vector<std::size_t> on_terrain;
  for (std::size_t p = 0; p < n; ++p)
    if (wanted[p] && height[p] <= limit)  // NaN: the terrain is unknown there
      on_terrain.push_back(p);
  // Rounds until nothing moves: the terrain under a bush's rim returns from the lawn inwards.
  // Each round counts links in the labels as the round found them.
  std::size_t moved = 0;
  for (bool again = true; again;) {
    const std::vector<int> before = labels;
    again = false;
    for (const std::size_t p : on_terrain) {
      if (!isOfClass(before[p], object_class, ObjectClass::Vegetation))
        continue;
      const int to = mostLinkedGround(p, graph, k, object_class, before);
      if (to < 0)
        continue;
      labels[p] = to;
      ++moved;
      again = true;
    }
  }
  return moved;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
