// The object level of IMRG against constructed scenes with known parts: a gable-roofed house
// with walls, two touching tree crowns and a crown leaning on the house, on flat ground; and a
// wire of two spans meeting at a cross arm. Also the link counting between segments and the
// links the fragment absorption after the assembly may use.
#include "segmentation/scenes.h"

#include <pcl_ls3d/segmentation/fragment_absorption.h>
#include <pcl_ls3d/segmentation/ground_filter.h>
#include <pcl_ls3d/segmentation/multi_rule_region_growing.h>
#include <pcl_ls3d/segmentation/object_assembly.h>
#include <pcl_ls3d/segmentation/segment_adjacency.h>
#include <pcl_ls3d/synth/scene.h>

#include <pcl/search/kdtree.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

using Segmenter = pcl_ls3d::MultiRuleRegionGrowing<pcl::PointXYZ>;
using Cloud = seg_test::Cloud;

namespace {

/// Part of the scene each point belongs to.
enum Part
{
  GROUND,
  ROOF_A,
  ROOF_B,
  WALL,
  TREE_1,
  TREE_2,
  TREE_3,
  SPAN_1,
  SPAN_2,
  ARM,
  CHIMNEY
};

void
add(Cloud& c, std::vector<int>& part, std::size_t from, Part p)
{
  part.resize(c.size(), p);
  for (std::size_t i = from; i < c.size(); ++i)
    part[i] = p;
}

/// Per part: the share of its points held by the segment that holds most of them, and that
/// segment's label.
std::map<int, std::pair<double, int>>
largestShares(const std::vector<int>& labels, const std::vector<int>& part)
{
  std::map<int, std::map<int, std::size_t>> count;
  std::map<int, std::size_t> total;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    ++count[part[i]][labels[i]];
    ++total[part[i]];
  }
  std::map<int, std::pair<double, int>> out;
  for (const auto& [p, by_label] : count) {
    std::size_t best = 0;
    int label = -1;
    for (const auto& [l, n] : by_label)
      if (l >= 0 && n > best) {
        best = n;
        label = l;
      }
    out[p] = {static_cast<double>(best) / static_cast<double>(total[p]), label};
  }
  return out;
}

std::vector<int>
extractLabels(Segmenter& s, const Cloud::Ptr& c, Segmenter::Level level)
{
  s.setInputCloud(c);
  s.setOutputLevel(level);
  std::vector<pcl::PointIndices> clusters;
  s.extract(clusters);
  EXPECT_FALSE(clusters.empty());
  return s.getPointLabels();
}

}  // namespace

TEST(ObjectAssembly, HouseTreesAndGroundBecomeWholeObjects)
{
  std::mt19937 rng(21);
  Cloud::Ptr c(new Cloud);
  std::vector<int> part;
  std::uniform_real_distribution<float> u(-0.02f, 0.02f);
  // Ground outside the house footprint [0, 12] × [0, 8].
  for (float x = -15.f; x <= 40.f; x += 0.3f)
    for (float y = -12.f; y <= 20.f; y += 0.3f)
      if (!(x > -0.1f && x < 12.1f && y > -0.1f && y < 8.1f))
        c->push_back(pcl::PointXYZ(x, y, u(rng)));
  add(*c, part, 0, GROUND);
  // Gable roof: eave 5 m at y = 0 and y = 8, ridge 7 m at y = 4 (27° pitch).
  std::size_t from = c->size();
  for (float x = 0.f; x <= 12.f; x += 0.25f)
    for (float y = 0.f; y < 4.f; y += 0.25f)
      c->push_back(pcl::PointXYZ(x, y, 5.f + 0.5f * y + u(rng)));
  add(*c, part, from, ROOF_A);
  from = c->size();
  for (float x = 0.f; x <= 12.f; x += 0.25f)
    for (float y = 4.f; y <= 8.f; y += 0.25f)
      c->push_back(pcl::PointXYZ(x, y, 5.f + 0.5f * (8.f - y) + u(rng)));
  add(*c, part, from, ROOF_B);
  // Sparse walls (0.5 m grid) on the four sides, up to the eave.
  from = c->size();
  seg_test::addWall(*c, 12.f, 0.f, 8.f, 0.3f, 4.8f, 0.5f, 0.02f, rng);
  seg_test::addWall(*c, 0.f, 0.f, 8.f, 0.3f, 4.8f, 0.5f, 0.02f, rng);
  for (float x = 0.f; x <= 12.f; x += 0.5f)
    for (float z = 0.3f; z <= 4.8f; z += 0.5f) {
      c->push_back(pcl::PointXYZ(x, 0.f + u(rng), z));
      c->push_back(pcl::PointXYZ(x, 8.f + u(rng), z));
    }
  add(*c, part, from, WALL);
  // Two touching crowns beside the house and a crown leaning on its far wall.
  from = c->size();
  seg_test::addBlob(*c, 25.f, 2.f, 6.f, 3.f, 2500, rng);
  add(*c, part, from, TREE_1);
  from = c->size();
  seg_test::addBlob(*c, 25.f, 7.5f, 6.f, 3.f, 2500, rng);
  add(*c, part, from, TREE_2);
  from = c->size();
  seg_test::addBlob(*c, 15.f, 4.f, 6.f, 2.8f, 2000, rng);
  add(*c, part, from, TREE_3);

  Segmenter s;
  auto shares = largestShares(extractLabels(s, c, Segmenter::Level::Objects), part);
  const auto& kinds = s.getAssemblyReport().kind_count;
  EXPECT_GT(kinds[static_cast<int>(pcl_ls3d::segmentation::SegmentKind::Rough)], 0u);
  // The house (both roof planes and the walls) is one object; so is the ground.
  EXPECT_GE(shares[ROOF_A].first, 0.95);
  EXPECT_EQ(shares[ROOF_A].second, shares[ROOF_B].second);
  EXPECT_GE(shares[ROOF_B].first, 0.95);
  EXPECT_EQ(shares[WALL].second, shares[ROOF_A].second);
  EXPECT_GE(shares[WALL].first, 0.6);  // wall feet join the ground
  EXPECT_GE(shares[GROUND].first, 0.98);
  // Touching crowns form one group, apart from the house and from the ground.
  EXPECT_GE(shares[TREE_1].first, 0.9);
  EXPECT_EQ(shares[TREE_1].second, shares[TREE_2].second);
  EXPECT_NE(shares[TREE_1].second, shares[ROOF_A].second);
  EXPECT_NE(shares[TREE_1].second, shares[GROUND].second);
  // The crown leaning on the house stays a tree: it never joins the roof.
  EXPECT_GE(shares[TREE_3].first, 0.8);
  EXPECT_NE(shares[TREE_3].second, shares[ROOF_A].second);

  // Plane level: the gable is two planes.
  Segmenter planes;
  shares = largestShares(extractLabels(planes, c, Segmenter::Level::Planes), part);
  EXPECT_GE(shares[ROOF_A].first, 0.8);
  EXPECT_GE(shares[ROOF_B].first, 0.8);
  EXPECT_NE(shares[ROOF_A].second, shares[ROOF_B].second);
}

TEST(ObjectAssembly, RoofStepAndChimneyJoinTheirBuilding)
{
  // A house whose annex roof lies 3 m below the main roof, 0.4 m beside it in plan, with no
  // wall points between the levels (too far apart for any k-NN link); a dense chimney 1.5 m
  // above the main roof whose nearest neighbours are all its own points; a tree beside the
  // annex. The house (both roofs and the chimney) is one object, the tree another.
  std::mt19937 rng(23);
  Cloud::Ptr c(new Cloud);
  std::vector<int> part;
  std::uniform_real_distribution<float> u(-0.02f, 0.02f);  // roofs as smooth as the ground
  for (float x = -10.f; x <= 35.f; x += 0.3f)
    for (float y = -10.f; y <= 20.f; y += 0.3f)
      if (!(x > -0.1f && x < 16.1f && y > -0.1f && y < 10.1f))
        c->push_back(pcl::PointXYZ(x, y, u(rng)));
  add(*c, part, 0, GROUND);
  std::size_t from = c->size();
  seg_test::addPlane(*c, 0.f, 10.f, 0.f, 10.f, 8.f, 0.3f, 0.02f, rng);
  add(*c, part, from, ROOF_A);
  from = c->size();
  seg_test::addPlane(*c, 10.4f, 16.f, 0.f, 10.f, 5.f, 0.3f, 0.02f, rng);
  add(*c, part, from, ROOF_B);
  from = c->size();
  seg_test::addBlob(*c, 3.f, 3.f, 9.5f, 0.4f, 200, rng);
  add(*c, part, from, CHIMNEY);
  from = c->size();
  seg_test::addBlob(*c, 24.f, 5.f, 5.f, 3.f, 2500, rng);
  add(*c, part, from, TREE_1);

  Segmenter s;
  auto shares = largestShares(extractLabels(s, c, Segmenter::Level::Objects), part);
  EXPECT_GE(shares[ROOF_A].first, 0.95);
  EXPECT_GE(shares[ROOF_B].first, 0.95);
  EXPECT_EQ(shares[ROOF_B].second, shares[ROOF_A].second);
  EXPECT_GE(shares[CHIMNEY].first, 0.9);
  EXPECT_EQ(shares[CHIMNEY].second, shares[ROOF_A].second);
  EXPECT_GE(shares[TREE_1].first, 0.9);
  EXPECT_NE(shares[TREE_1].second, shares[ROOF_A].second);
  EXPECT_NE(shares[GROUND].second, shares[ROOF_A].second);
}

TEST(ObjectAssembly, WireSpansStaySeparateAtTheirCrossArm)
{
  std::mt19937 rng(22);
  Cloud::Ptr c(new Cloud);
  std::vector<int> part;
  std::uniform_real_distribution<float> u(-0.02f, 0.02f);
  seg_test::addPlane(*c, -5.f, 65.f, -8.f, 8.f, 0.f, 0.5f, 0.02f, rng);
  add(*c, part, 0, GROUND);
  // Two spans of one conductor along x, sagging 0.9 m, hanging 0.5 m below a 6 m cross arm.
  const auto span = [&](float x0) {
    for (float t = 0.f; t <= 30.f; t += 0.3f) {
      const float sag = 0.9f * (1.f - (2.f * t / 30.f - 1.f) * (2.f * t / 30.f - 1.f));
      c->push_back(pcl::PointXYZ(x0 + t, u(rng), 12.f - sag + u(rng)));
    }
  };
  std::size_t from = c->size();
  span(0.f);
  add(*c, part, from, SPAN_1);
  from = c->size();
  span(30.3f);
  add(*c, part, from, SPAN_2);
  from = c->size();
  for (float y = -3.f; y <= 3.f; y += 0.3f)
    c->push_back(pcl::PointXYZ(30.15f + u(rng), y, 12.5f + u(rng)));
  add(*c, part, from, ARM);

  Segmenter s;
  const auto shares = largestShares(extractLabels(s, c, Segmenter::Level::Objects), part);
  EXPECT_GE(shares.at(SPAN_1).first, 0.9);
  EXPECT_GE(shares.at(SPAN_2).first, 0.9);
  EXPECT_NE(shares.at(SPAN_1).second, shares.at(SPAN_2).second);
}

TEST(ObjectAssembly, SegmentAdjacencyCountsShortLinksOnly)
{
  // Points 0,1 in segment 0; 2 in segment 1; 3 in segment 2 far away; 4 unlabelled.
  const std::vector<Eigen::Vector3f> pts{{0, 0, 0}, {1, 0, 0}, {1.5f, 0, 0}, {9, 0, 0}, {2, 0, 0}};
  const std::vector<int> labels{0, 0, 1, 2, -1};
  // k = 2: 0 -> {1, 2}, 1 -> {2, 0}, 2 -> {1, 4}, 3 -> {2, -1}, 4 -> {2, 1}.
  const std::vector<int> graph{1, 2, 2, 0, 1, 4, 2, -1, 2, 1};
  auto links = pcl_ls3d::segmentation::segmentAdjacency(pts, graph, 2, labels, 10.0);
  ASSERT_EQ(links.size(), 2u);
  EXPECT_EQ(links[0].a, 0);
  EXPECT_EQ(links[0].b, 1);
  EXPECT_EQ(links[0].links, 3u);  // 0->2, 1->2, 2->1
  EXPECT_EQ(links[1].a, 1);
  EXPECT_EQ(links[1].b, 2);
  EXPECT_EQ(links[1].links, 1u);  // 3->2, 7.5 long
  links = pcl_ls3d::segmentation::segmentAdjacency(pts, graph, 2, labels, 1.0);
  ASSERT_EQ(links.size(), 1u);
  EXPECT_EQ(links[0].links, 2u);  // 0->2 is 1.5 long: only 1->2 and 2->1 remain
}

namespace {

/// k-NN graph (k neighbours per point, self excluded) for assembleObjects().
std::vector<int>
knnGraph(const std::vector<Eigen::Vector3f>& pts, int k)
{
  Cloud::Ptr c(new Cloud);
  for (const auto& p : pts)
    c->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  pcl::search::KdTree<pcl::PointXYZ> tree;
  tree.setInputCloud(c);
  std::vector<int> graph(pts.size() * static_cast<std::size_t>(k), -1);
  pcl::Indices nn;
  std::vector<float> d2;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    tree.nearestKSearch((*c)[i], k + 1, nn, d2);
    int g = 0;
    for (const auto q : nn)
      if (static_cast<std::size_t>(q) != i && g < k)
        graph[i * static_cast<std::size_t>(k) + static_cast<std::size_t>(g++)] = q;
  }
  return graph;
}

namespace sg = pcl_ls3d::segmentation;

/// A constructed scene for assembleObjects(): each point with its segment label (the part of
/// the scene it belongs to) and its plane-fit residual.
struct Scene
{
  std::vector<Eigen::Vector3f> pts;
  std::vector<int> labels;
  std::vector<float> residuals;

  void
  push(const Eigen::Vector3f& p, int label, float residual)
  {
    pts.push_back(p);
    labels.push_back(label);
    residuals.push_back(residual);
  }

  void
  push(float x, float y, float z, int label, float residual)
  {
    push(Eigen::Vector3f(x, y, z), label, residual);
  }

  /// Walls of a 10 m x 10 m house with a flat roof at 6 m: the sides y = 0, y = 10, x = 0 and
  /// (if east) x = 10 on a 0.5 m grid from 0.5 m to 5.5 m, noise n(rng) across each wall.
  void
  addHouseWalls(int label, std::uniform_real_distribution<float>& n, std::mt19937& rng, bool east = true)
  {
    for (float t = 0.f; t <= 10.f; t += 0.5f)
      for (float z = 0.5f; z <= 5.5f; z += 0.5f) {
        push(t, n(rng), z, label, 0.01f);
        push(t, 10.f + n(rng), z, label, 0.01f);
        push(n(rng), t, z, label, 0.01f);
        if (east)
          push(10.f + n(rng), t, z, label, 0.01f);
      }
  }

  /// Ground around that house: a 0.3 m grid over [-8, 22] x [-8, 18], noise n(rng) in z,
  /// outside the house's plan [-0.3, 10.3] x [south, 10.3].
  void
  addGroundAroundHouse(int label, std::uniform_real_distribution<float>& n, std::mt19937& rng,
                       float south = -0.3f)
  {
    for (float x = -8.f; x <= 22.f; x += 0.3f)
      for (float y = -8.f; y <= 18.f; y += 0.3f)
        if (x < -0.3f || x > 10.3f || y < south || y > 10.3f)
          push(x, y, n(rng), label, 0.01f);
  }

  /// count rough points (residual 0.2) in the ball of radius r at c, drawn by rejection from
  /// the cube of b(rng), b uniform in [-1, 1].
  void
  addBall(const Eigen::Vector3f& c, float r, int count, int label, std::uniform_real_distribution<float>& b,
          std::mt19937& rng)
  {
    for (int i = 0; i < count;) {
      const Eigen::Vector3f d(b(rng), b(rng), b(rng));
      if (d.norm() <= 1.f) {
        push(c + r * d, label, 0.2f);
        ++i;
      }
    }
  }

  /// Output labels of assembleObjects() on the 16-NN graph, with the ground given per point.
  std::vector<int>
  assemble(const sg::AssemblySettings& a, const std::vector<char>& ground,
           sg::AssemblyReport* report = nullptr) const
  {
    std::vector<int> out = labels;
    const sg::AssemblyReport rep = sg::assembleObjects(pts, knnGraph(pts, 16), 16, residuals, ground, a, out);
    if (report)
      *report = rep;
    return out;
  }

  /// ... with the ground found by groundPoints() on cells of ground_cell.
  std::vector<int>
  assemble(const sg::AssemblySettings& a, double ground_cell, sg::AssemblyReport* report = nullptr) const
  {
    sg::GroundFilterSettings gf;
    gf.cell = ground_cell;
    return assemble(a, sg::groundPoints(pts, gf), report);
  }

  /// Output label (of out, from assemble()) holding most points of input label part.
  int
  labelOf(int part, const std::vector<int>& out) const
  {
    std::map<int, std::size_t> count;
    for (std::size_t i = 0; i < labels.size(); ++i)
      if (labels[i] == part)
        ++count[out[i]];
    return std::max_element(count.begin(), count.end(), [](auto& x, auto& y) { return x.second < y.second; })
        ->first;
  }
};

}  // namespace

// Grass 15-28 cm high along a hedge and in a patch of a lawn: within the ground filter's
// 0.3 m, so the filter keeps it and it stays in the ground segment. It stands 15-28 noise levels
// (ground residual 0.01; the limit is 6) above the terrain plane around it, so it leaves the
// ground: the strip along the hedge joins the hedge, the patch becomes its own object, and the
// terrain stays one ground object. With raised_noise_multiple 0 (the filter alone) both stay in the ground.
TEST(ObjectAssembly, GrassAboveTheTerrainPlaneLeavesTheGround)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> n(-0.02f, 0.02f), u(0.f, 1.f);
  Scene scene;
  std::vector<int> part;
  enum
  {
    TERRAIN,
    HEDGE,
    STRIP,
    PATCH
  };
  const auto inStrip = [](float x, float y) { return x >= 5.f && x <= 17.f && y > 6.5f && y <= 7.5f; };
  const auto inPatch = [](float x, float y) { return x >= 21.f && x <= 23.f && y >= 21.f && y <= 23.f; };
  for (float x = 0.f; x <= 30.f; x += 0.3f)
    for (float y = 0.f; y <= 30.f; y += 0.3f) {
      const bool grass = inStrip(x, y) || inPatch(x, y);  // the scanner sees the grass's top
      scene.push(x, y, grass ? 0.15f + 0.13f * u(rng) : n(rng), 0, grass ? 0.05f : 0.01f);
      part.push_back(inStrip(x, y) ? STRIP : inPatch(x, y) ? PATCH : TERRAIN);
    }
  for (int i = 0; i < 1800; ++i) {  // hedge 12 m x 1.5 m, 0.4-2.5 m high, its own segment
    scene.push(5.f + 12.f * u(rng), 5.f + 1.5f * u(rng), 0.4f + 2.1f * u(rng), 1, 0.1f);
    part.push_back(HEDGE);
  }
  sg::GroundFilterSettings gf;
  gf.cell = 0.6;
  const std::vector<char> ground = sg::groundPoints(scene.pts, gf);
  std::size_t grass = 0, grass_kept = 0;
  for (std::size_t i = 0; i < part.size(); ++i)
    if (part[i] == STRIP || part[i] == PATCH) {
      ++grass;
      grass_kept += ground[i];
    }
  ASSERT_GT(grass_kept, grass * 9 / 10);  // the filter alone would keep the grass

  sg::AssemblySettings a;
  a.max_link_length = 0.8;
  const std::vector<int> on = scene.assemble(a, ground);
  const auto share = [&](const std::vector<int>& l, int p, int label) {
    std::size_t in = 0, total = 0;
    for (std::size_t i = 0; i < l.size(); ++i)
      if (part[i] == p) {
        ++total;
        in += l[i] == label;
      }
    return static_cast<double>(in) / static_cast<double>(total);
  };
  const int terrain = on[0], hedge = on[part.size() - 1];
  ASSERT_EQ(part[0], TERRAIN);
  EXPECT_GE(share(on, TERRAIN, terrain), 0.99);
  EXPECT_GE(share(on, STRIP, hedge), 0.9);  // the strip joined the hedge
  EXPECT_LE(share(on, PATCH, terrain), 0.1);
  EXPECT_LE(share(on, PATCH, hedge), 0.0);  // the patch is its own object

  a.raised_noise_multiple = 0.0;
  const std::vector<int> off = scene.assemble(a, ground);
  EXPECT_GE(share(off, STRIP, off[0]), 0.9);
  EXPECT_GE(share(off, PATCH, off[0]), 0.9);
}

// A hedge whose foot (0.4-0.9 m above the terrain) the growing and merging left in the ground
// segment, and a patch of low vegetation (0.35-0.5 m) in the middle of a lawn, also in the
// ground segment. The ground filter rejects both; they leave the ground: the foot joins the
// hedge, the patch becomes its own object, the terrain stays one ground object. With
// detach_raised_points off, both stay in the ground (what the IGN tiles showed: class 3/4
// points inside ground segments).
TEST(ObjectAssembly, RaisedPointsLeaveTheGroundSegment)
{
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> n(-0.02f, 0.02f), u(0.f, 1.f);
  Scene scene;
  std::vector<int> part;
  enum
  {
    TERRAIN,
    FOOT,
    HEDGE,
    PATCH
  };
  for (float x = 0.f; x <= 30.f; x += 0.3f)
    for (float y = 0.f; y <= 30.f; y += 0.3f) {
      scene.push(x, y, n(rng), 0, 0.01f);
      part.push_back(TERRAIN);
    }
  // Hedge 12 m x 1.5 m at x in [5, 17], y in [5, 6.5]: foot in the ground segment (label 0),
  // the rest its own rough segment (label 1).
  for (int i = 0; i < 1800; ++i) {
    const float z = 0.4f + 2.1f * u(rng);
    scene.push(5.f + 12.f * u(rng), 5.f + 1.5f * u(rng), z, z < 0.9f ? 0 : 1, 0.1f);
    part.push_back(z < 0.9f ? FOOT : HEDGE);
  }
  // Low vegetation patch 2 m x 2 m at (22, 22), in the ground segment.
  for (int i = 0; i < 120; ++i) {
    scene.push(21.f + 2.f * u(rng), 21.f + 2.f * u(rng), 0.35f + 0.15f * u(rng), 0, 0.1f);
    part.push_back(PATCH);
  }
  sg::AssemblySettings a;
  a.max_link_length = 0.8;

  // Label holding most points of a part, and that share.
  const auto majority = [&](const std::vector<int>& l, int p) {
    std::map<int, std::size_t> count;
    std::size_t total = 0;
    for (std::size_t i = 0; i < l.size(); ++i)
      if (part[i] == p) {
        ++count[l[i]];
        ++total;
      }
    const auto best =
        std::max_element(count.begin(), count.end(), [](auto& x, auto& y) { return x.second < y.second; });
    return std::make_pair(best->first, static_cast<double>(best->second) / total);
  };

  sg::AssemblyReport rep;
  const std::vector<int> on = scene.assemble(a, 0.6, &rep);
  EXPECT_GT(rep.detached_points, 300u);
  const auto terrain = majority(on, TERRAIN), foot = majority(on, FOOT), hedge = majority(on, HEDGE),
             patch = majority(on, PATCH);
  EXPECT_GE(terrain.second, 0.99);
  EXPECT_GE(hedge.second, 0.99);
  EXPECT_EQ(foot.first, hedge.first);  // the foot joined the hedge
  EXPECT_GE(foot.second, 0.9);
  EXPECT_NE(patch.first, terrain.first);  // the patch left the ground ...
  EXPECT_NE(patch.first, hedge.first);    // ... as its own object
  EXPECT_GE(patch.second, 0.9);

  a.detach_raised_points = false;
  sg::AssemblyReport rep_off;
  const std::vector<int> off = scene.assemble(a, 0.6, &rep_off);
  EXPECT_EQ(rep_off.detached_points, 0u);
  EXPECT_EQ(majority(off, FOOT).first, majority(off, TERRAIN).first);
  EXPECT_EQ(majority(off, PATCH).first, majority(off, TERRAIN).first);
}

// A crown leaning over the edge of a flat roof touches nothing but the roof, and the house is
// more than 20 times its size: by contact alone it would "sit on" the building like a chimney.
// A rough group joins a building only by lying on its roof in plan, and most of this crown is
// outside the roof: it stays its own object. A chimney (rough too) in the middle of the roof
// still joins.
TEST(ObjectAssembly, CrownLeaningOverARoofStaysATree)
{
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> n(-0.02f, 0.02f), u(-1.f, 1.f);
  Scene scene;
  enum
  {
    ROOF,
    WALL,
    GROUND,
    CROWN,
    CHIMNEY
  };
  for (float x = 0.f; x <= 10.f; x += 0.25f)
    for (float y = 0.f; y <= 10.f; y += 0.25f)
      scene.push(x, y, 6.f + n(rng), ROOF, 0.01f);
  scene.addHouseWalls(WALL, n, rng);
  scene.addGroundAroundHouse(GROUND, n, rng);
  // Crown: 80 points in a ball of radius 1.2 m centred 1.2 m outside the east eave, its lower
  // part resting on the roof edge; no trunk (it reaches the roof, not the ground).
  for (int i = 0; i < 80;) {
    const Eigen::Vector3f d(u(rng), u(rng), u(rng));
    if (d.norm() > 1.f)
      continue;
    const Eigen::Vector3f p = Eigen::Vector3f(11.2f, 5.f, 7.f) + 1.2f * d;
    if (p.x() < 10.f && p.z() < 6.1f)
      continue;  // not inside the roof
    scene.push(p.x(), p.y(), p.z(), CROWN, 0.2f);
    ++i;
  }
  // Chimney: 60 scattered points in a 0.8 m box on the middle of the roof.
  for (int i = 0; i < 60; ++i)
    scene.push(5.f + 0.4f * u(rng), 5.f + 0.4f * u(rng), 6.9f + 0.7f * u(rng), CHIMNEY, 0.2f);

  sg::AssemblySettings a;
  a.max_link_length = 0.8;
  const std::vector<int> out = scene.assemble(a, 0.6);
  const auto labelOf = [&](int part) { return scene.labelOf(part, out); };
  EXPECT_EQ(labelOf(WALL), labelOf(ROOF));
  EXPECT_EQ(labelOf(CHIMNEY), labelOf(ROOF));
  EXPECT_NE(labelOf(CROWN), labelOf(ROOF));
  EXPECT_NE(labelOf(CROWN), labelOf(GROUND));
}

// Two sparse crowns (300 points in 4 m cubes, about 0.6 m apart inside) whose facing sides are
// 0.8 m apart: their k-NN graphs link them through edges of 0.8-1.2 m. Rough segments touch
// each other only through links up to rough_link_length (0.75 m here), so the two trees stay
// two objects, while the two halves of one crown still join. With rough_link_length off
// (= max_link_length, 1.2 m) the crowns join: generated scene seed 2's tree 11 and tree 28,
// 1.3 m apart, were one segment.
TEST(ObjectAssembly, NeighbouringCrownsStayTwoTrees)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-2.f, 2.f);
  Scene scene;
  const auto crown = [&](float cx, int left, int right) {
    for (int i = 0; i < 300; ++i) {
      const Eigen::Vector3f d(u(rng), u(rng), u(rng));
      scene.push(Eigen::Vector3f(cx, 0.f, 6.f) + d, d.x() < 0.f ? left : right, 0.2f);
    }
  };
  crown(0.f, 0, 1);   // crown A in two segments, x in [-2, 2]
  crown(4.8f, 2, 2);  // crown B, x in [2.8, 6.8]
  std::vector<char> ground(scene.pts.size(), 0);
  // Flat ground far below (the noise unit of the roughness: crowns are rough against it).
  for (float x = -6.f; x <= 11.f; x += 0.5f)
    for (float y = -5.f; y <= 5.f; y += 0.5f) {
      scene.push(x, y, 0.f, 3, 0.01f);
      ground.push_back(1);
    }
  sg::AssemblySettings a;
  a.max_link_length = 1.2;
  a.rough_link_length = 0.75;
  const std::size_t a_right =
      static_cast<std::size_t>(std::find(scene.labels.begin(), scene.labels.end(), 1) - scene.labels.begin());
  std::vector<int> out = scene.assemble(a, ground);
  EXPECT_EQ(out[0], out[a_right]);  // A's halves join
  EXPECT_NE(out[0], out[599]);      // A and B do not
  a.rough_link_length = 0.0;
  out = scene.assemble(a, ground);
  EXPECT_EQ(out[0], out[599]);
}

namespace {

/// Points of a generated scene inside the plane-level segments whose majority is a roof plane:
/// roof points of that plane, wall points, and points of another roof plane.
struct RoofPlaneContents
{
  std::size_t own = 0, wall = 0, other_plane = 0;
};

RoofPlaneContents
roofPlaneContents(std::uint32_t seed)
{
  pcl_ls3d::synth::SceneSettings settings;
  settings.seed = seed;
  settings.size_x = settings.size_y = 100.0;
  const auto scene = pcl_ls3d::synth::makeScene(settings);
  RoofPlaneContents out;
  if (!scene.cloud || scene.cloud->empty())
    return out;
  Cloud::Ptr c(new Cloud);
  for (const auto& p : *scene.cloud)
    c->push_back(pcl::PointXYZ(p.x, p.y, p.z));
  Segmenter s;
  const std::vector<int> labels = extractLabels(s, c, Segmenter::Level::Planes);
  std::map<int, std::map<int, std::size_t>> votes;
  for (std::size_t i = 0; i < labels.size(); ++i)
    if (labels[i] >= 0)
      ++votes[labels[i]][scene.plane_id[i]];
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] < 0)
      continue;
    const auto& v = votes[labels[i]];
    const int plane =
        std::max_element(v.begin(), v.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;
    if (plane < 0)
      continue;  // not a roof-plane segment
    const int id = scene.object_id[i];
    if (scene.plane_id[i] == plane)
      ++out.own;
    else if (scene.plane_id[i] >= 0)
      ++out.other_plane;
    else if (id >= 0 &&
             scene.objects[static_cast<std::size_t>(id)].type == pcl_ls3d::synth::ObjectType::BUILDING)
      ++out.wall;
  }
  return out;
}

}  // namespace

// Plane level on generated scenes: fragments join a plane only through links from points on
// its tangent plane (within growth radius x sin N_t) whose normals agree with it, so the wall
// fragments under the eaves and the fragments of a roof plane across the ridge stay out of a
// roof-plane segment. Seed 1 (one flat roof): 162 wall points in it before, 30 after. Seed 2
// (six planes): 112 points of another roof plane before (265 wall points), 73 after (89).
TEST(ObjectAssembly, RoofPlanesHoldNoWallOrNeighbourFragments)
{
  const RoofPlaneContents one = roofPlaneContents(1);
  EXPECT_GT(one.own, 1500u);
  EXPECT_LE(one.wall, 80u) << one.wall << " wall points in roof-plane segments";
  const RoofPlaneContents two = roofPlaneContents(2);
  EXPECT_GT(two.own, 2300u);
  EXPECT_LE(two.wall, 150u) << two.wall << " wall points in roof-plane segments";
  EXPECT_LE(two.other_plane, 95u) << two.other_plane << " points of another roof plane";
}

// The east facade of a building that stands outside the tile's west edge (77050_627755): all
// the tile holds of it is a 2.5 m strip of its flat roof and, under the eaves, a facade of
// four storeys with 1 m deep balconies (rough, as scattered as a crown). The facade is larger
// than the roof strip, so the size ratio that keeps crowns off roofs kept it out; it lies
// under the roof in plan and below it, so it joins. A rough roof unit on the strip, larger
// than a fifth of the strip but not of strip and facade, then joins too: the building stays
// a building although its rough facade now outweighs its roof. A crown resting on the roof
// strip (above it, larger than a fifth of the building) and a tree beside the facade stay
// trees.
TEST(ObjectAssembly, FacadeUnderAnEdgeRoofStripJoinsIt)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> n(-0.02f, 0.02f), u(0.f, 1.f), b(-1.f, 1.f);
  Scene scene;
  enum
  {
    ROOF,
    GROUND,
    CROWN,
    TREE,
    UNIT,
    STOREY
  };  // storeys: STOREY + 0..3
  for (float x = 0.f; x <= 2.5f; x += 0.25f)
    for (float y = 0.f; y <= 10.f; y += 0.25f)
      scene.push({x, y, 15.f + n(rng)}, ROOF, 0.01f);
  for (int s = 0; s < 4; ++s)
    for (int i = 0; i < 160; ++i)
      scene.push({1.5f + u(rng), 10.f * u(rng), 0.5f + 3.4f * static_cast<float>(s) + 3.f * u(rng)},
                 STOREY + s, 0.2f);
  for (float x = 2.8f; x <= 20.f; x += 0.3f)
    for (float y = -6.f; y <= 16.f; y += 0.3f)
      scene.push({x, y, n(rng)}, GROUND, 0.01f);
  // rests on the roof strip, 15.3-17.7 m
  scene.addBall({1.25f, 8.5f, 16.5f}, 1.2f, 300, CROWN, b, rng);
  // 120 > 0.2 x 451 roof points, < 0.2 x 1091
  scene.addBall({1.25f, 2.f, 15.8f}, 0.5f, 120, UNIT, b, rng);
  scene.addBall({8.f, 5.f, 5.f}, 2.5f, 500, TREE, b, rng);  // beside the facade

  sg::AssemblySettings a;
  a.max_link_length = 0.8;
  const std::vector<int> out = scene.assemble(a, 0.6);
  const auto labelOf = [&](int part) { return scene.labelOf(part, out); };
  for (int s = 0; s < 4; ++s)
    EXPECT_EQ(labelOf(STOREY + s), labelOf(ROOF)) << "storey " << s;
  EXPECT_EQ(labelOf(UNIT), labelOf(ROOF));
  EXPECT_NE(labelOf(CROWN), labelOf(ROOF));
  EXPECT_NE(labelOf(TREE), labelOf(ROOF));
  EXPECT_NE(labelOf(TREE), labelOf(GROUND));
}

// A flat roof of gravel (point residuals 5 x the ground's, but a thin sheet at its own scale)
// with a crown touching its east eave (77060_627760). Taken as rough, the roof joined the
// crown rough-to-rough and its walls stayed apart; flat, it is a roof: walls join it, the
// crown stays a tree.
TEST(ObjectAssembly, RoughFlatRoofIsARoofNotATree)
{
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> n(-0.02f, 0.02f), gravel(-0.05f, 0.05f), b(-1.f, 1.f);
  Scene scene;
  enum
  {
    ROOF,
    WALL,
    GROUND,
    CROWN
  };
  for (float x = 0.f; x <= 10.f; x += 0.25f)
    for (float y = 0.f; y <= 10.f; y += 0.25f)
      scene.push(x, y, 6.f + gravel(rng), ROOF, 0.05f);
  scene.addHouseWalls(WALL, n, rng, /*east=*/false);
  scene.addGroundAroundHouse(GROUND, n, rng);
  // crown: radius 2 m, its west side on the eave at x = 10
  scene.addBall({12.f, 5.f, 6.5f}, 2.f, 400, CROWN, b, rng);
  sg::AssemblySettings a;
  a.max_link_length = 0.8;
  const std::vector<int> out = scene.assemble(a, 0.6);
  const auto labelOf = [&](int part) { return scene.labelOf(part, out); };
  EXPECT_EQ(labelOf(WALL), labelOf(ROOF));
  EXPECT_NE(labelOf(CROWN), labelOf(ROOF));
  EXPECT_NE(labelOf(CROWN), labelOf(GROUND));
}

// A crown overhanging the east eave of a flat roof (77055_627760: small crowns over low
// roofs): 100 points, a fifth of the building at most, two-thirds over the roof and a third
// beyond the eave, all above the roof. The roof's plan widened by footprint_margin held all of
// it, so the size ratio let it join like a chimney. The margin is for what hangs under the
// eaves: above the roof, a point in a margin cell that opens onto what lies beyond the roof
// does not count, so the crown stays a tree. A roof unit (2 m x 2 m, 1.2 m high) hides the
// roof under it, so the cells it covers hold no roof point and are margin cells too; they are
// enclosed by roof cells and by each other, and the unit still joins, as does a chimney.
TEST(ObjectAssembly, CrownOverhangingAnEaveStaysATree)
{
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> n(-0.02f, 0.02f), u(0.f, 1.f), b(-1.f, 1.f);
  Scene scene;
  enum
  {
    ROOF,
    WALL,
    GROUND,
    CROWN,
    UNIT,
    CHIMNEY
  };
  for (float x = 0.f; x <= 10.f; x += 0.25f)
    for (float y = 0.f; y <= 10.f; y += 0.25f)
      if (x <= 2.f || x >= 4.f || y <= 2.f || y >= 4.f)  // no roof under the unit
        scene.push(x, y, 6.f + n(rng), ROOF, 0.01f);
  scene.addHouseWalls(WALL, n, rng);
  scene.addGroundAroundHouse(GROUND, n, rng);
  // crown: radius 0.9 m, 6.3-8.1 m, x 9.3-11.1
  scene.addBall({10.2f, 5.f, 7.2f}, 0.9f, 100, CROWN, b, rng);
  for (int i = 0; i < 150; ++i)  // roof unit: scattered returns in a 2 m x 2 m x 1.2 m box
    scene.push(2.f + 2.f * u(rng), 2.f + 2.f * u(rng), 6.f + 1.2f * u(rng), UNIT, 0.2f);
  for (int i = 0; i < 60; ++i)
    scene.push(7.f + 0.4f * b(rng), 7.f + 0.4f * b(rng), 6.9f + 0.7f * b(rng), CHIMNEY, 0.2f);

  sg::AssemblySettings a;
  a.max_link_length = 0.8;
  const std::vector<int> out = scene.assemble(a, 0.6);
  const auto labelOf = [&](int part) { return scene.labelOf(part, out); };
  EXPECT_EQ(labelOf(WALL), labelOf(ROOF));
  EXPECT_EQ(labelOf(UNIT), labelOf(ROOF));
  EXPECT_EQ(labelOf(CHIMNEY), labelOf(ROOF));
  EXPECT_NE(labelOf(CROWN), labelOf(ROOF));
  EXPECT_NE(labelOf(CROWN), labelOf(GROUND));
}

// The lowest balcony row of a facade under the eaves and the hedge at the facade's foot
// (77055_627755: the south facade of the tall building): both rough, 0.3 m apart, so they
// joined rough-to-rough as one "tree", and that group, half of it outside the roof, no longer
// lay on the building's footprint. What hangs under a roof (footprint_share of it under the
// roof's own cells, below the roof) does not join rough-to-rough with what lies mostly outside
// every roof: the balcony row joins the house (it hangs under the roof), the hedge stays a
// tree.
TEST(ObjectAssembly, BalconyRowUnderTheEavesIsNotPartOfTheHedgeBelow)
{
  std::mt19937 rng(19);
  std::uniform_real_distribution<float> n(-0.02f, 0.02f), u(0.f, 1.f);
  Scene scene;
  enum
  {
    ROOF,
    WALL,
    GROUND,
    BALCONY,
    HEDGE
  };
  for (float x = 0.f; x <= 10.f; x += 0.25f)  // the roof's eaves reach 0.6 m past the walls
    for (float y = -0.6f; y <= 10.f; y += 0.25f)
      scene.push(x, y, 6.f + n(rng), ROOF, 0.01f);
  scene.addHouseWalls(WALL, n, rng);
  scene.addGroundAroundHouse(GROUND, n, rng, /*south=*/-0.7f);  // under the eaves too
  for (int i = 0; i < 150; ++i)  // balcony row under the eaves: 2.5-3.5 m, 0.5 m deep
    scene.push(2.f + 6.f * u(rng), -0.5f * u(rng), 2.5f + u(rng), BALCONY, 0.2f);
  for (int i = 0; i < 400; ++i)  // hedge at the facade's foot: 0.3-2.4 m, 0.8-2.4 m out
    scene.push(2.f + 6.f * u(rng), -0.8f - 1.6f * u(rng), 0.3f + 2.1f * u(rng), HEDGE, 0.2f);

  sg::AssemblySettings a;
  a.max_link_length = 0.8;
  const std::vector<int> out = scene.assemble(a, 0.6);
  const auto labelOf = [&](int part) { return scene.labelOf(part, out); };
  EXPECT_EQ(labelOf(WALL), labelOf(ROOF));
  EXPECT_EQ(labelOf(BALCONY), labelOf(ROOF));
  EXPECT_NE(labelOf(HEDGE), labelOf(ROOF));
  EXPECT_NE(labelOf(HEDGE), labelOf(GROUND));
}

// The absorption after the assembly counts short links only, none from rough into ground
// (absorptionContact): a bush of a few points on a lawn, whose k-NN rows hold a lawn point
// beside it and a point of a crown over 4 m away, stays its own object; a crown fragment
// touching its crown joins it. The graph is written out: on sparse airborne data a far crown
// does appear among a bush's nearest neighbours once its own points and the lawn's are used up.
TEST(ObjectAssembly, AbsorptionJoinsOnlyTouchingFragments)
{
  using pcl_ls3d::segmentation::SegmentKind;
  const int k = 4;
  std::vector<Eigen::Vector3f> points;
  std::vector<SegmentKind> kind;
  std::vector<int> labels, graph;
  const auto addPoint = [&](float x, float y, float z, SegmentKind sk, int label) {
    points.emplace_back(x, y, z);
    kind.push_back(sk);
    labels.push_back(label);
    graph.resize(graph.size() + k, -1);
    return points.size() - 1;
  };
  const auto link = [&](std::size_t p, std::initializer_list<std::size_t> row) {
    std::size_t c = 0;
    for (const std::size_t q : row)
      graph[p * k + c++] = static_cast<int>(q);
  };
  // Lawn (segment 0, 40 points) and crown (segment 1, 40 points, 3 m up): 0.3 m grids of two
  // rows, each point linked to the previous and the next point of its segment.
  std::vector<std::size_t> lawn, crown;
  for (int i = 0; i < 40; ++i)
    lawn.push_back(addPoint(0.3f * static_cast<float>(i % 20), 0.3f * static_cast<float>(i / 20), 0.0f,
                            SegmentKind::Ground, 0));
  for (int i = 0; i < 40; ++i)
    crown.push_back(addPoint(9.0f + 0.3f * static_cast<float>(i % 20), 0.3f * static_cast<float>(i / 20),
                             3.0f, SegmentKind::Rough, 1));
  for (const auto* part : {&lawn, &crown})
    for (std::size_t i = 0; i < part->size(); ++i) {
      const std::size_t next = i + 1 < part->size() ? i + 1 : i - 1;
      link((*part)[i], {(*part)[i > 0 ? i - 1 : 1], (*part)[next]});
    }
  // Bush (segment 2): 4 rough points 0.3 m over the lawn's end at x = 5.7; rows: two bush
  // points, one lawn point 0.32-0.37 m away, one crown point 4.1-4.4 m away.
  std::vector<std::size_t> bush;
  for (int i = 0; i < 4; ++i)
    bush.push_back(addPoint(5.6f + 0.1f * static_cast<float>(i), 0.1f, 0.3f, SegmentKind::Rough, 2));
  for (std::size_t i = 0; i < 4; ++i)
    link(bush[i], {bush[(i + 1) % 4], bush[(i + 2) % 4], lawn[19], crown[0]});
  // Crown fragment (segment 3): 3 rough points 0.3 m under the crown's first points.
  std::vector<std::size_t> leaves;
  for (int i = 0; i < 3; ++i)
    leaves.push_back(addPoint(9.0f + 0.3f * static_cast<float>(i), 0.0f, 2.7f, SegmentKind::Rough, 3));
  for (std::size_t i = 0; i < 3; ++i)
    link(leaves[i], {leaves[(i + 1) % 3], crown[i]});

  // 0.9 m: longer than every link inside a part and the leaves' (0.3 m), shorter than the
  // bush's crown links.
  const double max_link = 0.9;
  std::vector<int> assembled = labels;
  EXPECT_EQ(pcl_ls3d::segmentation::absorbFragments(
                graph, k, assembled, 10, pcl_ls3d::segmentation::absorptionContact(points, kind, max_link)),
            1u)
      << "only the leaves join";
  EXPECT_NE(assembled[bush[0]], assembled[crown[0]]) << "the bush joined a crown 4 m away";
  EXPECT_NE(assembled[bush[0]], assembled[lawn[0]]) << "the bush joined the ground";
  EXPECT_EQ(assembled[leaves[0]], assembled[crown[0]]) << "a touching crown fragment stays apart";

  // Without the length limit (the rule before: only no rough point into the ground) the
  // bush's crown links decide and the bush becomes part of the tree.
  std::vector<int> unlimited = labels;
  EXPECT_EQ(pcl_ls3d::segmentation::absorbFragments(
                graph, k, unlimited, 10,
                [&kind](int p, int q) {
                  return !(kind[static_cast<std::size_t>(p)] == SegmentKind::Rough &&
                           kind[static_cast<std::size_t>(q)] == SegmentKind::Ground);
                }),
            2u);
  EXPECT_EQ(unlimited[bush[0]], unlimited[crown[0]]);

  // Sizes that differ: no link counts, nothing is absorbed.
  std::vector<int> mismatched = labels;
  const std::vector<SegmentKind> short_kinds(3, SegmentKind::Rough);
  EXPECT_EQ(
      pcl_ls3d::segmentation::absorbFragments(
          graph, k, mismatched, 10, pcl_ls3d::segmentation::absorptionContact(points, short_kinds, max_link)),
      0u);
}
