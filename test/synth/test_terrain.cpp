// Tests of Terrain (relief in every direction, analytic gradient) and the building index.
#include <pcl_ls3d/synth/buildings.h>
#include <pcl_ls3d/synth/terrain.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace pcl_ls3d::synth;

// Slope exists in every horizontal direction (so horizontal shifts are determinable): the RMS
// directional derivative in each of 12 directions is at least 30 % of the largest one.
TEST(Synth, TerrainReliefInEveryDirection)
{
  for (std::uint32_t seed : {1u, 2u, 3u, 7u}) {
    const Terrain t(seed);
    std::vector<double> rms;
    for (int k = 0; k < 12; ++k) {
      const Eigen::Vector2d u(std::cos(k * M_PI / 12), std::sin(k * M_PI / 12));
      double sum = 0.0;
      int n = 0;
      for (double x = -150; x <= 150; x += 5)
        for (double y = -150; y <= 150; y += 5, ++n)
          sum += std::pow(u.dot(t.gradient(x, y)), 2);
      rms.push_back(std::sqrt(sum / n));
    }
    const auto mm = std::minmax_element(rms.begin(), rms.end());
    EXPECT_GT(*mm.first, 0.3 * *mm.second) << "seed " << seed;
    EXPECT_GT(*mm.first, 0.03) << "seed " << seed;  // a few cm per m at least
  }
}

// The analytic gradient matches central differences; the normal is a unit upward vector.
TEST(Synth, TerrainGradientAndNormal)
{
  const Terrain t(5, 10.0, 60.0);
  const double h = 1e-4;
  for (double x = -100; x <= 100; x += 37)
    for (double y = -100; y <= 100; y += 41) {
      const Eigen::Vector2d g = t.gradient(x, y);
      EXPECT_NEAR(g.x(), (t.height(x + h, y) - t.height(x - h, y)) / (2 * h), 1e-6);
      EXPECT_NEAR(g.y(), (t.height(x, y + h) - t.height(x, y - h)) / (2 * h), 1e-6);
      const Eigen::Vector3d n = t.normal(x, y);
      EXPECT_NEAR(n.norm(), 1.0, 1e-12);
      EXPECT_GT(n.z(), 0.0);
      EXPECT_NEAR(n.head<2>().dot(Eigen::Vector2d(-g.y(), g.x())), 0.0, 1e-12);
    }
  // Relief scales the heights linearly.
  const Terrain t2(5, 20.0, 60.0);
  EXPECT_NEAR(t2.height(12.0, -7.0), 2.0 * t.height(12.0, -7.0), 1e-9);
}

// The grid index answers exactly as a scan over all footprints; buildings do not overlap.
TEST(Synth, BuildingIndexMatchesScan)
{
  const Terrain t(3);
  BuildingSettings bs;
  bs.per_hectare = 8.0;
  const auto buildings =
      placeBuildings(t, Eigen::AlignedBox2d(Eigen::Vector2d(-100, -100), Eigen::Vector2d(100, 100)), bs, 3);
  ASSERT_GT(buildings.size(), 10u);
  const BuildingSet set(buildings);
  for (double x = -110; x <= 110; x += 0.7)
    for (double y = -110; y <= 110; y += 0.9) {
      int scan = -1, count = 0;
      for (int i = 0; i < static_cast<int>(buildings.size()); ++i)
        if (buildings[i].contains(x, y)) {
          scan = i;
          ++count;
        }
      ASSERT_LE(count, 1);
      ASSERT_EQ(set.find(x, y), scan);
    }
  for (const auto& b : buildings)  // eave at least min_eave above the footprint centre
    EXPECT_GE(b.eave_z - t.height(b.centre.x(), b.centre.y()), bs.min_eave - 1e-9);
}
