// The progressive morphological ground filter against known truth: a sloped, curved terrain with
// a 24 m × 16 m building (6 m high) and a car-sized box (1.5 m); every terrain point must be
// ground and every roof or car point not, with windows wider than the building.
#include <pcl_ls3d/segmentation/ground_filter.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace pcl_ls3d::segmentation;

namespace {
float
terrain(float x, float y)
{
  return 0.15f * x + 2.f * std::sin(0.05f * y);  // 8.5° slope plus a 2 m swell
}

bool
inBuilding(float x, float y)
{
  return x > 10.f && x < 34.f && y > 20.f && y < 36.f;
}

bool
inCar(float x, float y)
{
  return x > 50.f && x < 54.5f && y > 10.f && y < 11.8f;
}
}  // namespace

TEST(GroundFilter, TerrainIsGroundRoofsAndCarsAreNot)
{
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.f, 70.f);
  std::normal_distribution<float> noise(0.f, 0.03f);
  std::vector<Eigen::Vector3f> pts;
  std::vector<int> truth;  // 1 terrain, 0 object
  for (int i = 0; i < 40000; ++i) {
    const float x = u(rng), y = u(rng);
    const float g = terrain(x, y);
    float z = g;
    int t = 1;
    if (inBuilding(x, y)) {
      z = terrain(34.f, 36.f) + 6.f;  // flat roof above the footprint's highest terrain
      t = 0;
    } else if (inCar(x, y)) {
      z = g + 1.5f;
      t = 0;
    }
    pts.emplace_back(x, y, z + noise(rng));
    truth.push_back(t);
  }
  GroundFilterSettings s;
  s.cell = 0.8;
  s.max_window = 40.0;
  const std::vector<char> ground = groundPoints(pts, s);
  ASSERT_EQ(ground.size(), pts.size());
  std::size_t wrong_terrain = 0, wrong_object = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    wrong_terrain += truth[i] == 1 && !ground[i];
    wrong_object += truth[i] == 0 && ground[i];
  }
  EXPECT_EQ(wrong_object, 0u);
  // A few terrain points at the building's foot may fall in cells opened by roof neighbours.
  EXPECT_LT(wrong_terrain, pts.size() / 200);

  // Windows narrower than the building cannot remove it: its interior stays "ground".
  s.max_window = 8.0;
  const std::vector<char> narrow = groundPoints(pts, s);
  std::size_t roof_kept = 0;
  for (std::size_t i = 0; i < pts.size(); ++i)
    roof_kept += truth[i] == 0 && narrow[i] && inBuilding(pts[i].x(), pts[i].y());
  EXPECT_GT(roof_kept, 1000u);
}

// A mountain slope of 40° (IGN's target_cloud_crop): within one 0.8 m cell the terrain rises
// 0.67 m, more than the 0.3 m the first window allows above the cell's lowest point, so a
// filter comparing with a flat cell kept only the lower part of each cell (on that file 56 % of
// the ground). The opened surface follows the slope within the cell: every terrain point is
// ground, while a 1.5 m high car and a shrub layer 1 m above the slope are not.
TEST(GroundFilter, SteepSlopeIsGround)
{
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0.f, 30.f);
  std::normal_distribution<float> noise(0.f, 0.03f);
  const float rise = std::tan(40.f * 3.14159265f / 180.f);
  std::vector<Eigen::Vector3f> pts;
  std::vector<int> truth;  // 1 terrain, 0 object
  for (int i = 0; i < 20000; ++i) {
    const float x = u(rng), y = u(rng);
    float z = rise * x;
    int t = 1;
    if (x > 10.f && x < 14.5f && y > 10.f && y < 11.8f) {
      z += 1.5f;
      t = 0;
    } else if (x > 20.f && x < 26.f && y > 20.f && y < 26.f && i % 2 == 0) {
      z += 1.f;
      t = 0;
    }
    pts.emplace_back(x, y, z + noise(rng));
    truth.push_back(t);
  }
  GroundFilterSettings s;
  s.cell = 0.8;
  s.max_window = 20.0;
  const std::vector<char> ground = groundPoints(pts, s);
  std::size_t terrain = 0, terrain_kept = 0, object_kept = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    terrain += truth[i];
    terrain_kept += truth[i] == 1 && ground[i];
    object_kept += truth[i] == 0 && ground[i];
  }
  EXPECT_GT(terrain_kept, terrain * 99 / 100);
  EXPECT_EQ(object_kept, 0u);
}

TEST(GroundFilter, LowestPointGridAndEmptyInput)
{
  const std::vector<Eigen::Vector3f> pts{{0.f, 0.f, 5.f}, {0.5f, 0.5f, 3.f}, {2.5f, 0.f, 1.f}};
  const LowestPointGrid grid(pts, 1.0);
  EXPECT_EQ(grid.cols(), 3);
  EXPECT_EQ(grid.rows(), 1);
  EXPECT_FLOAT_EQ(grid.lowest()[static_cast<std::size_t>(grid.cellOf(pts[0]))], 3.f);
  EXPECT_EQ(grid.lowestPoint()[static_cast<std::size_t>(grid.cellOf(pts[0]))], 1);
  EXPECT_TRUE(std::isnan(grid.lowest()[1]));  // nothing fell in the middle cell
  EXPECT_EQ(grid.lowestPoint()[1], -1);
  // Non-finite points take no part: the same grid, and they are not ground.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<Eigen::Vector3f> with_nan = pts;
  with_nan.emplace_back(nan, 0.f, 0.f);
  with_nan.emplace_back(0.2f, 0.2f, nan);
  const LowestPointGrid same(with_nan, 1.0);
  EXPECT_EQ(same.cols(), 3);
  EXPECT_EQ(same.rows(), 1);
  EXPECT_EQ(same.lowestPoint()[static_cast<std::size_t>(same.cellOf(pts[0]))], 1);
  const std::vector<char> ground = groundPoints(with_nan, {});
  ASSERT_EQ(ground.size(), 5u);
  EXPECT_EQ(ground[3], 0);
  EXPECT_EQ(ground[4], 0);
  EXPECT_EQ(ground[1], 1);
  EXPECT_EQ(groundPoints({{nan, nan, nan}}, {}), std::vector<char>{0});
  EXPECT_TRUE(groundPoints({}, {}).empty());
}

// Heights above the terrain plane against the known terrain: on the sloped, curved terrain of
// the first test (noise σ 3 cm), grass points 5–30 cm above it — which the filter keeps as
// ground — come out at their true height within a few centimetres, terrain points near 0;
// points not asked for, and points with too few or only collinear ground points around, are NaN.
TEST(GroundFilter, HeightAboveTerrainFollowsTheTerrainPlane)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.f, 40.f), lift(0.05f, 0.3f);
  std::normal_distribution<float> noise(0.f, 0.03f);
  std::vector<Eigen::Vector3f> pts;
  std::vector<float> truth;
  for (int i = 0; i < 30000; ++i) {
    const float x = u(rng), y = u(rng);
    const float h = i % 10 == 0 ? lift(rng) : 0.f;  // every tenth point is grass
    pts.emplace_back(x, y, terrain(x, y) + h + noise(rng));
    truth.push_back(h);
  }
  const std::vector<char> ground = groundPoints(pts, GroundFilterSettings{});
  std::vector<char> wanted(pts.size(), 1);
  wanted[1] = 0;
  const std::vector<float> height = heightAboveTerrain(pts, ground, wanted, 1.5);
  EXPECT_TRUE(std::isnan(height[1]));
  double worst = 0.0, sum = 0.0;
  std::size_t grass = 0, grass_kept = 0;
  for (std::size_t i = 2; i < pts.size(); ++i) {
    ASSERT_FALSE(std::isnan(height[i])) << i;
    const double error = height[i] - truth[i];
    worst = std::max(worst, std::abs(error));
    sum += error * error;
    if (truth[i] > 0.f) {
      ++grass;
      grass_kept += ground[i];
    }
  }
  EXPECT_GT(grass_kept, grass / 2);                          // the filter alone keeps most grass as ground
  EXPECT_LT(std::sqrt(sum / double(pts.size() - 2)), 0.04);  // ≈ the noise
  EXPECT_LT(worst, 0.2);

  // A lone point far from the ground, and ground points on one line: no plane.
  std::vector<Eigen::Vector3f> line;
  for (int i = 0; i < 20; ++i)
    line.emplace_back(0.1f * float(i), 0.f, 0.f);
  line.emplace_back(1.f, 0.5f, 0.3f);
  line.emplace_back(30.f, 30.f, 0.f);
  std::vector<char> on_line(line.size(), 1);
  on_line[20] = on_line[21] = 0;
  const std::vector<float> h_line = heightAboveTerrain(line, on_line, std::vector<char>(line.size(), 1), 1.5);
  EXPECT_TRUE(std::isnan(h_line[20]));
  EXPECT_TRUE(std::isnan(h_line[21]));
  // Sizes that do not match: nothing computed (no read past the end).
  const std::vector<float> h_short = heightAboveTerrain(line, std::vector<char>(3, 1), on_line, 1.5);
  EXPECT_TRUE(std::all_of(h_short.begin(), h_short.end(), [](float h) { return std::isnan(h); }));
}

// A stray point 100 km away, in both x and y, must not widen the window the terrain plane is
// fitted in (the curved terrain would then pass for grass): every height stays as it was.
TEST(GroundFilter, HeightAboveTerrainIgnoresAFarOutlier)
{
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.f, 40.f);
  std::normal_distribution<float> noise(0.f, 0.03f);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 20000; ++i) {
    const float x = u(rng), y = u(rng);
    pts.emplace_back(x, y, terrain(x, y) + 3.f * std::sin(0.3f * x) + noise(rng));  // curved
  }
  std::vector<char> ground(pts.size(), 1), wanted(pts.size(), 1);
  const std::vector<float> before = heightAboveTerrain(pts, ground, wanted, 1.5);
  pts.emplace_back(1.0e5f, 1.0e5f, 0.f);
  ground.push_back(1);
  wanted.push_back(1);
  const std::vector<float> after = heightAboveTerrain(pts, ground, wanted, 1.5);
  double worst = 0.0;
  for (std::size_t i = 0; i < before.size(); ++i)
    worst = std::max(worst, double(std::abs(after[i] - before[i])));
  EXPECT_LT(worst, 1e-4);
  EXPECT_TRUE(std::isnan(after.back()));  // alone in its window
}
