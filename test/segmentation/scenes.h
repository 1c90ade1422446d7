#pragma once
/// \file scenes.h
/// \brief Small constructed scenes with known answers for the segmentation tests.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <random>

namespace seg_test {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// Grid on the plane z = z0 over [x0, x1] × [y0, y1] with step h and uniform noise ±noise in z.
inline void
addPlane(Cloud& c, float x0, float x1, float y0, float y1, float z0, float h, float noise, std::mt19937& rng)
{
  std::uniform_real_distribution<float> u(-noise, noise);
  for (float x = x0; x <= x1 + 1e-4f; x += h)
    for (float y = y0; y <= y1 + 1e-4f; y += h)
      c.push_back(pcl::PointXYZ(x, y, z0 + u(rng)));
}

/// Vertical wall x = x0 over [y0, y1] × [z0, z1] with step h and noise ±noise in x.
inline void
addWall(Cloud& c, float x0, float y0, float y1, float z0, float z1, float h, float noise, std::mt19937& rng)
{
  std::uniform_real_distribution<float> u(-noise, noise);
  for (float y = y0; y <= y1 + 1e-4f; y += h)
    for (float z = z0; z <= z1 + 1e-4f; z += h)
      c.push_back(pcl::PointXYZ(x0 + u(rng), y, z));
}

/// Vertical pole at (x, y) from z0 to z1, step h, radial jitter ±noise.
inline void
addPole(Cloud& c, float x, float y, float z0, float z1, float h, float noise, std::mt19937& rng)
{
  std::uniform_real_distribution<float> u(-noise, noise);
  for (float z = z0; z <= z1 + 1e-4f; z += h)
    c.push_back(pcl::PointXYZ(x + u(rng), y + u(rng), z));
}

/// n points uniform in a ball of radius r at (cx, cy, cz): a tree crown.
inline void
addBlob(Cloud& c, float cx, float cy, float cz, float r, int n, std::mt19937& rng)
{
  std::uniform_real_distribution<float> u(-r, r);
  int added = 0;
  while (added < n) {
    const float x = u(rng), y = u(rng), z = u(rng);
    if (x * x + y * y + z * z > r * r)
      continue;
    c.push_back(pcl::PointXYZ(cx + x, cy + y, cz + z));
    ++added;
  }
}

}  // namespace seg_test
