/// \file segment_adjacency.cpp
/// \brief Link counts between touching segments.

#include <pcl_ls3d/segmentation/segment_adjacency.h>

#include <algorithm>
#include <cstdint>

namespace pcl_ls3d {
namespace segmentation {

std::vector<SegmentLink>
segmentAdjacency(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& graph, int graph_k,
                 const std::vector<int>& labels, double max_length)
{
  std::vector<SegmentLink> out;
  const auto k = static_cast<std::size_t>(std::max(0, graph_k));
  if (k == 0 || graph.size() != labels.size() * k || points.size() != labels.size())
    return out;
  const double max_sq = max_length * max_length;
  // One key per link, sorted: cheaper than a hash map at millions of links.
  std::vector<std::uint64_t> keys;
  for (std::size_t p = 0; p < labels.size(); ++p) {
    const int a = labels[p];
    if (a < 0)
      continue;
    for (std::size_t c = 0; c < k; ++c) {
      const int q = graph[p * k + c];
      if (q < 0)
        continue;
      const int b = labels[static_cast<std::size_t>(q)];
      if (b < 0 || b == a || (points[p] - points[static_cast<std::size_t>(q)]).squaredNorm() > max_sq)
        continue;
      const auto lo = static_cast<std::uint64_t>(std::min(a, b));
      const auto hi = static_cast<std::uint64_t>(std::max(a, b));
      keys.push_back((lo << 32) | hi);
    }
  }
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    while (j < keys.size() && keys[j] == keys[i])
      ++j;
    SegmentLink l;
    l.a = static_cast<int>(keys[i] >> 32);
    l.b = static_cast<int>(keys[i] & 0xffffffffu);
    l.links = j - i;
    out.push_back(l);
    i = j;
  }
  return out;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
