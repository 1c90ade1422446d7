/// \file fragment_absorption.cpp
/// \brief Absorption of tiny segments into the most connected adjacent segment.

#include <pcl_ls3d/segmentation/fragment_absorption.h>

#include <algorithm>
#include <numeric>
#include <unordered_map>

namespace pcl_ls3d {
namespace segmentation {

namespace {

/// The segments as member lists under a union-find, fragments merged into their neighbours.
class Absorption
{
public:
  Absorption(const std::vector<int>& graph, int graph_k, const std::vector<int>& labels, int n_seg,
             const std::function<bool(int, int)>& linkable)
      : graph_(graph), graph_k_(graph_k), labels_(labels), linkable_(linkable), members_(n_seg),
        parent_(n_seg)
  {
    for (std::size_t p = 0; p < labels.size(); ++p)
      if (labels[p] >= 0)
        members_[labels[p]].push_back(static_cast<int>(p));
    std::iota(parent_.begin(), parent_.end(), 0);
  }

  const std::vector<std::vector<int>>&
  members() const
  {
    return members_;
  }

  int
  find(int s)
  {
    while (parent_[s] != s)
      s = parent_[s] = parent_[parent_[s]];
    return s;
  }

  /// Merges segment s into the segment its points have most graph links to (ties: the larger
  /// segment, then the lower label); false when it has no linkable neighbour.
  bool
  absorb(int s)
  {
    countLinks(s);
    const int best = mostLinked();
    if (best < 0)
      return false;
    parent_[s] = best;
    members_[best].insert(members_[best].end(), members_[s].begin(), members_[s].end());
    members_[s].clear();
    members_[s].shrink_to_fit();
    return true;
  }

private:
  /// Graph links from the points of s to each other segment (by its root).
  void
  countLinks(int s)
  {
    links_.clear();
    for (const int p : members_[s])
      for (int g = 0; g < graph_k_; ++g) {
        const int q = graph_[static_cast<std::size_t>(p) * graph_k_ + g];
        if (q < 0 || labels_[q] < 0 || (linkable_ && !linkable_(p, q)))
          continue;
        const int t = find(labels_[q]);
        if (t != s)
          ++links_[t];
      }
  }

  int
  mostLinked() const
  {
    int best = -1, best_links = 0;
    for (const auto& [t, c] : links_)
      if (c > best_links ||
          (c == best_links && (members_[t].size() > members_[best].size() ||
                               (members_[t].size() == members_[best].size() && t < best)))) {
        best = t;
        best_links = c;
      }
    return best;
  }

  const std::vector<int>& graph_;
  const int graph_k_;
  const std::vector<int>& labels_;
  const std::function<bool(int, int)>& linkable_;
  std::vector<std::vector<int>> members_;
  std::vector<int> parent_;
  std::unordered_map<int, int> links_;
};

/// Segments smallest first (stable: equal sizes keep their label order).
std::vector<int>
smallestFirst(const std::vector<std::vector<int>>& members)
{
  std::vector<int> order(members.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return members[a].size() < members[b].size(); });
  return order;
}

/// Labels of the roots, dense from 0.
void
relabelRoots(Absorption& absorption, int n_seg, std::vector<int>& labels)
{
  std::vector<int> dense(n_seg, -1);
  int next = 0;
  for (int& l : labels) {
    if (l < 0)
      continue;
    const int root = absorption.find(l);
    if (dense[root] < 0)
      dense[root] = next++;
    l = dense[root];
  }
}

}  // namespace

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
  Absorption absorption(graph, graph_k, labels, n_seg, linkable);
  const std::vector<int> order = smallestFirst(absorption.members());
  std::vector<std::size_t> initial_size(n_seg);
  for (int s = 0; s < n_seg; ++s)
    initial_size[s] = absorption.members()[s].size();
  std::size_t absorbed = 0;
  for (const int s : order) {
    if (initial_size[s] >= min_size)
      break;  // sizes only grow: every later segment is large enough too
    if (absorption.find(s) != s || absorption.members()[s].size() >= min_size)
      continue;
    if (absorption.absorb(s))
      ++absorbed;
  }
  if (absorbed == 0)
    return 0;
  relabelRoots(absorption, n_seg, labels);
  return absorbed;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
