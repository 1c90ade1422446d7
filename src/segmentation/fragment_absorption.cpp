/// \file fragment_absorption.cpp
/// \brief Absorption of tiny segments into the most connected adjacent segment.

#include <pcl_ls3d/segmentation/fragment_absorption.h>

#include <algorithm>
#include <numeric>
#include <unordered_map>

namespace pcl_ls3d {
namespace segmentation {

std::size_t
absorbFragments(const std::vector<int>& graph, int graph_k, std::vector<int>& labels, std::size_t min_size,
                const std::function<bool(int, int)>& linkable)
{
  if (min_size < 2 || graph_k < 1 || labels.empty() ||
      graph.size() != labels.size() * static_cast<std::size_t>(graph_k))
    return 0;
  const int n_seg = *std::max_element(labels.begin(), labels.end()) + 1;
  if (n_seg < 2)
    return 0;
  std::vector<std::vector<int>> members(n_seg);
  for (std::size_t p = 0; p < labels.size(); ++p)
    if (labels[p] >= 0)
      members[labels[p]].push_back(static_cast<int>(p));
  std::vector<int> parent(n_seg);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int s) {
    while (parent[s] != s)
      s = parent[s] = parent[parent[s]];
    return s;
  };
  std::vector<int> order(n_seg);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return members[a].size() < members[b].size(); });

  std::vector<std::size_t> initial_size(n_seg);
  for (int s = 0; s < n_seg; ++s)
    initial_size[s] = members[s].size();

  std::size_t absorbed = 0;
  std::unordered_map<int, int> links;
  for (const int s : order) {
    if (initial_size[s] >= min_size)
      break;  // sizes only grow: every later segment is large enough too
    if (find(s) != s || members[s].size() >= min_size)
      continue;
    links.clear();
    for (const int p : members[s])
      for (int g = 0; g < graph_k; ++g) {
        const int q = graph[static_cast<std::size_t>(p) * graph_k + g];
        if (q < 0 || labels[q] < 0 || (linkable && !linkable(p, q)))
          continue;
        const int t = find(labels[q]);
        if (t != s)
          ++links[t];
      }
    int best = -1, best_links = 0;
    for (const auto& [t, c] : links)
      if (c > best_links || (c == best_links && (members[t].size() > members[best].size() ||
                                                 (members[t].size() == members[best].size() && t < best)))) {
        best = t;
        best_links = c;
      }
    if (best < 0)
      continue;
    parent[s] = best;
    members[best].insert(members[best].end(), members[s].begin(), members[s].end());
    members[s].clear();
    members[s].shrink_to_fit();
    ++absorbed;
  }
  if (absorbed == 0)
    return 0;
  std::vector<int> dense(n_seg, -1);
  int next = 0;
  for (int& l : labels) {
    if (l < 0)
      continue;
    const int root = find(l);
    if (dense[root] < 0)
      dense[root] = next++;
    l = dense[root];
  }
  return absorbed;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
