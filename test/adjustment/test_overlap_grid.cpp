// OverlapGrid (engine overlap culling) is conservative: it never rejects a query that has a
// target point within reach (checked by brute force), and it rejects most far queries.
#include <pcl_ls3d/adjustment/overlap_grid.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using pcl_ls3d::OverlapGrid;
using pcl_ls3d::PointVectorTargetSurface;

namespace {
double
nearestDistance(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& q)
{
  double best = std::numeric_limits<double>::max();
  for (const auto& p : pts)
    best = std::min(best, (p - q).norm());
  return best;
}
}  // namespace

TEST(OverlapGrid, NeverCullsAQueryWithATargetPointWithinReach)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // A bumpy 40 m × 20 m target patch with a hole, and queries around and above it.
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 3000; ++i) {
    const double x = 40.0 * u(rng), y = 20.0 * u(rng);
    if (std::hypot(x - 20.0, y - 10.0) < 5.0)
      continue;
    pts.emplace_back(x, y, 3.0 * std::sin(0.3 * x) + 0.5 * u(rng));
  }
  const PointVectorTargetSurface target(pts);
  for (const double reach : {0.3, 1.0, 2.5}) {
    OverlapGrid grid;
    ASSERT_TRUE(grid.build(target, reach));
    int near = 0, far = 0, far_culled = 0;
    for (int i = 0; i < 3000; ++i) {
      const Eigen::Vector3d q(-10.0 + 60.0 * u(rng), -10.0 + 40.0 * u(rng), -6.0 + 12.0 * u(rng));
      const double d = nearestDistance(pts, q);
      if (d <= reach) {
        ++near;
        EXPECT_TRUE(grid.mayOverlap(q)) << "reach " << reach << " distance " << d;
      } else if (d > 3.0 * reach + 1.0) {
        ++far;
        far_culled += !grid.mayOverlap(q);
      }
    }
    EXPECT_GT(near, 20) << reach;
    // Cells of edge `reach` dilated by one cell: queries farther than ~3 reach are culled.
    EXPECT_GT(far_culled, far * 9 / 10) << reach;
  }
}

TEST(OverlapGrid, UnlimitedReachOrEmptyTargetCullsNothing)
{
  const PointVectorTargetSurface target(
      {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)});
  OverlapGrid grid;
  EXPECT_FALSE(grid.build(target, std::numeric_limits<double>::max()));
  EXPECT_TRUE(grid.mayOverlap(Eigen::Vector3d(1e6, 1e6, 1e6)));
  EXPECT_FALSE(grid.build(target, std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(grid.build(PointVectorTargetSurface({}), 1.0));
  EXPECT_TRUE(grid.mayOverlap(Eigen::Vector3d(5, 5, 5)));
  ASSERT_TRUE(grid.build(target, 0.5));
  EXPECT_FALSE(grid.mayOverlap(Eigen::Vector3d(5, 5, 5)));
  EXPECT_TRUE(grid.mayOverlap(Eigen::Vector3d(0.2, 0.2, 0.3)));
}
