// What lies on the terrain is ground (terrain_contact.h): constructed objects with known classes
// through returnTerrainPoints().
#include <pcl_ls3d/segmentation/terrain_contact.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

using pcl_ls3d::segmentation::ObjectClass;
using pcl_ls3d::segmentation::returnTerrainPoints;

namespace {

constexpr int kGraphK = 8;
constexpr double kLimit = 0.06;  // 3 ground residuals of 2 cm
constexpr double kHalfWidth = 1.5;

enum Object
{
  kLawn,
  kBush,
  kHouse,
  kObjects
};

struct Scene
{
  std::vector<Eigen::Vector3f> points;
  std::vector<int> labels;
  std::vector<char> ground;

  std::size_t
  add(float x, float y, float z, int label, bool kept)
  {
    points.emplace_back(x, y, z);
    labels.push_back(label);
    ground.push_back(kept ? 1 : 0);
    return points.size() - 1;
  }

  /// Brute-force k nearest neighbours (the scene is small).
  std::vector<int>
  graph() const
  {
    std::vector<int> g(points.size() * kGraphK, -1);
    std::vector<std::size_t> order(points.size());
    for (std::size_t p = 0; p < points.size(); ++p) {
      std::iota(order.begin(), order.end(), 0);
      const auto dist = [&](std::size_t q) { return (points[q] - points[p]).squaredNorm(); };
      std::partial_sort(order.begin(), order.begin() + kGraphK + 1, order.end(),
                        [&](std::size_t a, std::size_t b) { return dist(a) < dist(b); });
      for (int c = 0; c < kGraphK; ++c)
        g[p * kGraphK + c] = static_cast<int>(order[static_cast<std::size_t>(c) + 1]);
    }
    return g;
  }
};

std::vector<ObjectClass>
classesOfTheScene()
{
  std::vector<ObjectClass> c(kObjects);
  c[kLawn] = ObjectClass::Ground;
  c[kBush] = ObjectClass::Vegetation;
  c[kHouse] = ObjectClass::Building;
  return c;
}

}  // namespace

TEST(TerrainContact, GroundAtABushsFootJoinsTheLawnAndItsLeavesStay)
{
  // A sloping lawn (1:10, 2 cm noise) with a bush of radius 1.5 m at (5, 5). The bush object
  // also holds the terrain under its rim (the growth's mistake), leaves 0.15 m and more above
  // it that the filter keeps (within its 0.3 m), and its crown, which the filter rejects.
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.f, 0.02f);
  const auto terrain = [](float x, float) { return 0.1f * x; };
  Scene s;
  std::vector<std::size_t> foot, leaves, crown, wall_foot;
  for (float x = 0.f; x < 10.f; x += 0.25f)
    for (float y = 0.f; y < 10.f; y += 0.25f) {
      const float r = std::hypot(x - 5.f, y - 5.f);
      const float z = terrain(x, y) + noise(rng);
      if (r > 1.5f)
        s.add(x, y, z, kLawn, true);
      else if (r > 1.0f)
        foot.push_back(s.add(x, y, z, kBush, true));
      else if (r > 0.5f)
        leaves.push_back(s.add(x, y, terrain(x, y) + 0.15f + 0.1f * (1.f - r), kBush, true));
      else
        crown.push_back(s.add(x, y, terrain(x, y) + 1.0f, kBush, false));
    }
  // A house's wall reaching down to the terrain at x = 9: its foot is the building's.
  for (float y = 2.f; y < 4.f; y += 0.25f)
    for (float z = 0.f; z < 2.f; z += 0.25f)
      wall_foot.push_back(s.add(9.05f, y, terrain(9.05f, y) + z, kHouse, z == 0.f));
  std::vector<int> labels = s.labels;

  const std::size_t moved = returnTerrainPoints(s.points, s.ground, s.graph(), kGraphK, classesOfTheScene(),
                                                kLimit, kHalfWidth, labels);

  std::size_t foot_on_lawn = 0;
  for (const auto p : foot)
    foot_on_lawn += labels[p] == kLawn;
  // Noise of 2 cm against a 6 cm limit: nearly all of the foot returns, from the lawn inwards
  // (a point 3 sigma up stays).
  EXPECT_GE(foot_on_lawn, foot.size() * 95 / 100) << "of " << foot.size();
  EXPECT_EQ(moved, foot_on_lawn);
  for (const auto p : leaves)
    ASSERT_EQ(labels[p], kBush) << "a leaf 0.15 m up is no terrain";
  for (const auto p : crown)
    ASSERT_EQ(labels[p], kBush);
  for (const auto p : wall_foot)
    ASSERT_EQ(labels[p], kHouse) << "only vegetation objects give points back";
}

// A parked car that IMRG grew as a rough object (named car by its returns) holds the ground
// beside it like a bush's rim: its points at the terrain's level join the lawn, its body 1 m up
// (which the filter rejects) stays the car.
TEST(TerrainContact, GroundBesideACarJoinsTheLawn)
{
  std::mt19937 rng(9);
  std::normal_distribution<float> noise(0.f, 0.02f);
  Scene s;
  std::vector<std::size_t> rim, body;
  for (float x = 0.f; x < 10.f; x += 0.25f)
    for (float y = 0.f; y < 10.f; y += 0.25f) {
      const bool on_car = x > 3.f && x < 7.5f && y > 4.f && y < 5.8f;
      const bool beside = !on_car && x > 2.6f && x < 7.9f && y > 3.6f && y < 6.2f;
      if (on_car)
        body.push_back(s.add(x, y, 1.0f + noise(rng), kBush, false));
      else if (beside)
        rim.push_back(s.add(x, y, noise(rng), kBush, true));
      else
        s.add(x, y, noise(rng), kLawn, true);
    }
  std::vector<ObjectClass> classes = classesOfTheScene();
  classes[kBush] = ObjectClass::Car;
  std::vector<int> labels = s.labels;
  returnTerrainPoints(s.points, s.ground, s.graph(), kGraphK, classes, kLimit, kHalfWidth, labels);
  std::size_t rim_on_lawn = 0;
  for (const auto p : rim)
    rim_on_lawn += labels[p] == kLawn;
  EXPECT_GE(rim_on_lawn, rim.size() * 95 / 100) << "of " << rim.size();
  for (const auto p : body)
    ASSERT_EQ(labels[p], kBush);
}

TEST(TerrainContact, EnclosedGroundWithoutALinkToTheGroundStays)
{
  // A wide crown object holding terrain points in its middle, 3 m from any ground object:
  // none of their k-NN links reach the ground, so they stay.
  Scene s;
  for (float x = 0.f; x < 12.f; x += 0.25f)
    for (float y = 0.f; y < 4.f; y += 0.25f) {
      if (x < 2.f)
        s.add(x, y, 0.f, kLawn, true);
      else if (x < 6.f)
        s.add(x, y, 2.f + 0.3f * std::sin(3.f * x), kBush, false);  // crown
      else
        s.add(x, y, 0.f, kBush, true);  // terrain seen through it
    }
  std::vector<int> labels = s.labels;
  const std::size_t moved = returnTerrainPoints(s.points, s.ground, s.graph(), kGraphK, classesOfTheScene(),
                                                kLimit, kHalfWidth, labels);
  EXPECT_EQ(moved, 0u);
  EXPECT_EQ(labels, s.labels);
}

TEST(TerrainContact, EnclosedGroundLinkedByTerrainReturns)
{
  // Terrain seen through a crown, joined to the lawn by a strip of terrain points along y < 1
  // (the crown leaves it free): the chain brings all of it back, round by round.
  Scene s;
  std::vector<std::size_t> through_crown;
  for (float x = 0.f; x < 8.f; x += 0.25f)
    for (float y = 0.f; y < 4.f; y += 0.25f) {
      if (x < 2.f)
        s.add(x, y, 0.f, kLawn, true);
      else if (y < 1.f || x >= 5.f)
        through_crown.push_back(s.add(x, y, 0.f, kBush, true));
      else
        s.add(x, y, 2.f + 0.3f * std::sin(3.f * x), kBush, false);  // crown
    }
  std::vector<int> labels = s.labels;
  returnTerrainPoints(s.points, s.ground, s.graph(), kGraphK, classesOfTheScene(), kLimit, kHalfWidth,
                      labels);
  for (const auto p : through_crown)
    ASSERT_EQ(labels[p], kLawn) << "at " << s.points[p].transpose();
}

TEST(TerrainContact, BadArgumentsMoveNothing)
{
  Scene s;
  for (float x = 0.f; x < 3.f; x += 0.25f)
    for (float y = 0.f; y < 3.f; y += 0.25f)
      s.add(x, y, 0.f, x < 1.5f ? kLawn : kBush, true);
  const std::vector<int> graph = s.graph();
  std::vector<int> labels = s.labels;
  const auto classes = classesOfTheScene();
  EXPECT_EQ(returnTerrainPoints(s.points, s.ground, graph, kGraphK, classes, 0.0, kHalfWidth, labels), 0u);
  EXPECT_EQ(returnTerrainPoints(s.points, s.ground, graph, kGraphK - 1, classes, kLimit, kHalfWidth, labels),
            0u);
  std::vector<char> short_ground(s.ground.begin(), s.ground.end() - 1);
  EXPECT_EQ(returnTerrainPoints(s.points, short_ground, graph, kGraphK, classes, kLimit, kHalfWidth, labels),
            0u);
  EXPECT_EQ(labels, s.labels);
  // Points in no object, or in an object past the class list, are left alone.
  labels[0] = -1;
  labels[1] = kObjects + 3;
  const std::vector<int> odd = labels;
  EXPECT_GT(returnTerrainPoints(s.points, s.ground, graph, kGraphK, classes, kLimit, kHalfWidth, labels), 0u);
  EXPECT_EQ(labels[0], -1);
  EXPECT_EQ(labels[1], kObjects + 3);
}
