// VoxelIndex and the source thinning on cells far finer than the data's extent: voxel
// coordinates must not overflow (a plain double → int64 cast is undefined past 9.2e18 and put
// every point into one voxel), and far-apart voxels must not share a key.
#include <pcl_ls3d/adjustment/surface_matching_core.h>
#include <pcl_ls3d/common/voxel_index.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace pcl_ls3d;

namespace {

std::vector<Eigen::Vector3d>
lineOfPoints(int n, double spacing)
{
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i)
    points.emplace_back(spacing * i, 0.5 * spacing * i, 2.0);
  return points;
}

}  // namespace

TEST(VoxelCoordinate, SaturatesInsteadOfOverflowing)
{
  EXPECT_EQ(voxelCoordinate(2.5, 1.0), 2);
  EXPECT_EQ(voxelCoordinate(-0.5, 1.0), -1);
  EXPECT_EQ(voxelCoordinate(1.0, 1e-25), kVoxelCoordinateLimit);
  EXPECT_EQ(voxelCoordinate(-1.0, 1e-25), -kVoxelCoordinateLimit);
  EXPECT_EQ(voxelCoordinate(std::nan(""), 1.0), 0);
}

// A 1e-25 cell on metre coordinates: every point within the radius is still found.
TEST(VoxelIndex, TinyCellFindsEveryNeighbour)
{
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {5, 5, 5}};
  const VoxelIndex index(points, 1e-25);
  std::vector<int> found;
  index.radiusSearch({0.5, 0.0, 0.0}, 1.6, found);
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, (std::vector<int>{0, 1, 2}));
  index.nearestK({0.9, 0.0, 0.0}, 2, found);
  EXPECT_EQ(found, (std::vector<int>{1, 0}));
}

// Thinning at a voxel below the coordinates' resolution keeps every point (it kept one).
TEST(SourceThinning, VoxelFinerThanTheDataKeepsEveryPoint)
{
  const std::vector<Eigen::Vector3d> points = lineOfPoints(1000, 0.1);
  EXPECT_EQ(thinByVoxel(points, 1e-25).size(), points.size());
  EXPECT_EQ(thinByVoxel(points, 1e-20).size(), points.size());
  EXPECT_EQ(thinByVoxel(points, 0.0).size(), points.size());
}

// 2^21 voxels apart used to share a key (21 bits per axis, wrapped): the second point was lost.
TEST(SourceThinning, FarApartVoxelsAreKept)
{
  const double step = 1e-3;
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {step * (1 << 21) + 0.5 * step, 0, 0}};
  EXPECT_EQ(thinByVoxel(points, step).size(), 2u);
}

// Regular thinning still merges the points of one voxel: 800 points 0.125 apart in x (exact in
// binary) through 1 m voxels leave one point per voxel crossed.
TEST(SourceThinning, OnePointPerVoxel)
{
  const std::vector<Eigen::Vector3d> points = lineOfPoints(800, 0.125);
  const std::vector<int> kept = thinByVoxel(points, 1.0);
  EXPECT_EQ(kept.front(), 0);
  EXPECT_EQ(kept.size(), 100u);  // x crosses 100 voxels; y 50, always together with x
}
