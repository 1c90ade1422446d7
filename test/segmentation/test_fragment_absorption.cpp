// Fragment absorption: tiny segments join the neighbour they share most k-NN links with; large
// segments, unlabelled points and isolated fragments stay as they are.
#include <pcl_ls3d/segmentation/fragment_absorption.h>

#include <gtest/gtest.h>

#include <algorithm>

#include <vector>

using pcl_ls3d::segmentation::absorbFragments;

namespace {
/// Chain graph on a line of points: neighbours p−1 and p+1 (k = 2), −1 at the ends.
std::vector<int>
chainGraph(int n)
{
  std::vector<int> g(2 * n, -1);
  for (int p = 0; p < n; ++p) {
    g[2 * p] = p > 0 ? p - 1 : -1;
    g[2 * p + 1] = p + 1 < n ? p + 1 : -1;
  }
  return g;
}
}  // namespace

TEST(FragmentAbsorption, FragmentJoinsTheMostLinkedNeighbour)
{
  // Points 0..9 segment 0, 10..11 segment 1 (fragment), 12..21 segment 2.
  // The fragment links once to segment 0 and once to segment 2: tie -> larger (both 10) ->
  // smaller id 0. Make segment 2 larger so the tie goes to it instead.
  std::vector<int> labels(23, 0);
  for (int p = 10; p < 12; ++p)
    labels[p] = 1;
  for (int p = 12; p < 23; ++p)
    labels[p] = 2;
  const auto graph = chainGraph(23);
  EXPECT_EQ(absorbFragments(graph, 2, labels, 5), 1u);
  EXPECT_EQ(labels[10], labels[12]);
  EXPECT_EQ(labels[11], labels[22]);
  EXPECT_NE(labels[10], labels[0]);
  // Dense relabelling: two segments left, ids 0 and 1.
  EXPECT_EQ(*std::max_element(labels.begin(), labels.end()), 1);
}

TEST(FragmentAbsorption, ClusterOfFragmentsJoinsItselfAndStopsAtMinSize)
{
  // A 40-point segment (a chain) and a "crown" of ten 2-point fragments whose points link
  // only among themselves (a ring) plus one link from the big segment into the crown.
  // Links are counted from the fragment's own points, so the crown joins itself, stops once
  // every group has min_size = 8 points, and the big segment keeps exactly its 40 points.
  const int n = 60;
  std::vector<int> labels(n), graph(2 * n, -1);
  for (int p = 0; p < 40; ++p) {
    labels[p] = 0;
    graph[2 * p] = p > 0 ? p - 1 : -1;
    graph[2 * p + 1] = p + 1;  // 39 -> 40: the only link between the two
  }
  for (int p = 40; p < n; ++p) {
    labels[p] = 1 + (p - 40) / 2;
    graph[2 * p] = p > 40 ? p - 1 : n - 1;
    graph[2 * p + 1] = p + 1 < n ? p + 1 : 40;
  }
  EXPECT_GT(absorbFragments(graph, 2, labels, 8), 0u);
  std::vector<int> size(*std::max_element(labels.begin(), labels.end()) + 1, 0);
  for (int l : labels)
    ++size[l];
  for (int s : size)
    EXPECT_GE(s, 8);
  EXPECT_EQ(size[labels[0]], 40);
  for (int p = 40; p < n; ++p)
    EXPECT_NE(labels[p], labels[0]) << p;
  EXPECT_LT(size.size(), 10u);  // fragments did join
}

TEST(FragmentAbsorption, IsolatedFragmentsUnlabelledPointsAndOff)
{
  // Fragment 1 (points 5,6) is separated from segment 0 by unlabelled points: no target.
  std::vector<int> labels{0, 0, 0, -1, -1, 1, 1, -1};
  const auto graph = chainGraph(8);
  auto copy = labels;
  EXPECT_EQ(absorbFragments(graph, 2, copy, 10), 0u);
  EXPECT_EQ(copy, labels);
  EXPECT_EQ(absorbFragments(graph, 2, copy, 0), 0u);   // off
  EXPECT_EQ(absorbFragments(graph, 3, copy, 10), 0u);  // graph size mismatch: untouched
  EXPECT_EQ(copy, labels);
}
