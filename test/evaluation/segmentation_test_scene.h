#pragma once
// A small labelled scene for the segmentation tests, independent of the synth module: a gently
// sloped ground plane (class 2), a flat-roofed box building with sparse walls (6), two tree
// crowns (5) and a few unclassified points (1). Deterministic in the seed.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <random>

namespace pcl_ls3d_test {

inline pcl::PointCloud<pcl::PointXYZL>
makeSmallScene(unsigned seed = 1)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::normal_distribution<float> noise(0.f, 0.02f);
  pcl::PointCloud<pcl::PointXYZL> c;
  auto add = [&](float x, float y, float z, std::uint32_t l) {
    pcl::PointXYZL p;
    p.x = x + noise(rng);
    p.y = y + noise(rng);
    p.z = z + noise(rng);
    p.label = l;
    c.push_back(p);
  };
  auto ground = [](float x, float y) { return 0.02f * x + 0.01f * y; };
  // Building footprint [5, 17] × [5, 15], roof at 8 m above ground level 0.
  auto inBuilding = [](float x, float y) { return x > 5.f && x < 17.f && y > 5.f && y < 15.f; };
  const float trees[2][2] = {{-10.f, -8.f}, {-12.f, 10.f}};
  auto inCrown = [&](float x, float y) {
    for (const auto& t : trees)
      if ((x - t[0]) * (x - t[0]) + (y - t[1]) * (y - t[1]) < 9.f)
        return true;
    return false;
  };
  // Ground and roof: 6 pulses per m² over 40 m × 40 m.
  for (int i = 0; i < 9600; ++i) {
    const float x = -20.f + 40.f * u(rng), y = -20.f + 40.f * u(rng);
    if (inBuilding(x, y))
      add(x, y, 8.f, 6);
    else if (!inCrown(x, y))
      add(x, y, ground(x, y), 2);
  }
  // Walls: 2 points per m² on the four sides.
  for (int i = 0; i < 700; ++i) {
    const float t = u(rng), z = 8.f * u(rng);
    switch (i % 4) {
    case 0:
      add(5.f + 12.f * t, 5.f, z, 6);
      break;
    case 1:
      add(5.f + 12.f * t, 15.f, z, 6);
      break;
    case 2:
      add(5.f, 5.f + 10.f * t, z, 6);
      break;
    default:
      add(17.f, 5.f + 10.f * t, z, 6);
      break;
    }
  }
  // Tree crowns: points in an ellipsoid (radius 3 m, 2.5 m half height, centre 6 m up).
  for (const auto& t : trees)
    for (int i = 0; i < 1500;) {
      const float dx = 2.f * u(rng) - 1.f, dy = 2.f * u(rng) - 1.f, dz = 2.f * u(rng) - 1.f;
      if (dx * dx + dy * dy + dz * dz > 1.f)
        continue;
      add(t[0] + 3.f * dx, t[1] + 3.f * dy, ground(t[0], t[1]) + 6.f + 2.5f * dz, 5);
      ++i;
    }
  // A few unclassified points just above the ground: excluded from the evaluation.
  for (int i = 0; i < 30; ++i)
    add(-18.f + u(rng), 18.f + u(rng), 0.5f, 1);
  c.width = static_cast<std::uint32_t>(c.size());
  c.height = 1;
  c.is_dense = true;
  return c;
}

}  // namespace pcl_ls3d_test
