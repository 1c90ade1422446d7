// tin::enclosingTriangle against an exhaustive search over all triples (the definition: the
// enclosing triangle with the smallest sum of vertex distances, one through the nearest point
// when there is one), on random neighbourhoods inside, on the border of and outside the points.
#include <pcl_ls3d/rules/local_tin.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using pcl_ls3d::tin::containsOrigin;
using pcl_ls3d::tin::enclosingTriangle;

// Smallest distance sum over enclosing triangles, those through point 0 first; +inf if none.
double
exhaustiveBest(const std::vector<Eigen::Vector2d>& p)
{
  const double inf = std::numeric_limits<double>::infinity();
  double through_nearest = inf, any = inf;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        if (!containsOrigin(p[i], p[j], p[k]))
          continue;
        const double size = p[i].norm() + p[j].norm() + p[k].norm();
        (i == 0 ? through_nearest : any) = std::min(i == 0 ? through_nearest : any, size);
      }
  return through_nearest < inf ? through_nearest : any;
}

// k points in a disc of radius 1 around `centre` (the query is the origin), nearest first.
std::vector<Eigen::Vector2d>
neighbourhood(std::mt19937& rng, int k, const Eigen::Vector2d& centre)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector2d> p;
  while (static_cast<int>(p.size()) < k) {
    const Eigen::Vector2d d(u(rng), u(rng));
    if (d.squaredNorm() <= 1.0)
      p.push_back(centre + d);
  }
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return a.norm() < b.norm(); });
  return p;
}

TEST(LocalTin, EnclosingTriangleIsTheSmallestOfAnExhaustiveSearch)
{
  std::mt19937 rng(7);
  int found = 0, outside = 0;
  // Query at the centre, part-way out (border of the target) and beyond the points.
  for (const double offset : {0.0, 0.5, 0.9, 1.1, 2.0})
    for (const int k : {3, 4, 12, 36})
      for (int trial = 0; trial < 200; ++trial) {
        const double angle = 0.1 * trial;
        const auto p = neighbourhood(rng, k, offset * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
        std::array<int, 3> tri{{-1, -1, -1}};
        const bool ok = enclosingTriangle(p, tri);
        const double expected = exhaustiveBest(p);
        ASSERT_EQ(ok, std::isfinite(expected)) << "offset " << offset << " k " << k << " trial " << trial;
        if (!ok) {
          ++outside;
          continue;
        }
        ++found;
        EXPECT_TRUE(containsOrigin(p[tri[0]], p[tri[1]], p[tri[2]]));
        EXPECT_DOUBLE_EQ(p[tri[0]].norm() + p[tri[1]].norm() + p[tri[2]].norm(), expected);
      }
  // Both branches were exercised.
  EXPECT_GT(found, 1000);
  EXPECT_GT(outside, 500);
}

TEST(LocalTin, QueryOnAVertexOrAnEdgeIsEnclosed)
{
  // A neighbour at the query itself, and the query on the edge between two neighbours.
  const std::vector<Eigen::Vector2d> on_vertex{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {2.0, 2.0}};
  const std::vector<Eigen::Vector2d> on_edge{{0.0, 1.0}, {-1.0, 0.0}, {1.0, 0.0}, {0.0, 3.0}};
  std::array<int, 3> tri{};
  EXPECT_TRUE(enclosingTriangle(on_vertex, tri));
  EXPECT_TRUE(enclosingTriangle(on_edge, tri));
  EXPECT_EQ(tri, (std::array<int, 3>{{0, 1, 2}}));
  // All points in a half-plane: nothing encloses the query.
  const std::vector<Eigen::Vector2d> one_sided{{0.1, 0.5}, {0.2, -0.5}, {1.0, 0.0}, {2.0, 1.0}};
  EXPECT_FALSE(enclosingTriangle(one_sided, tri));
}

}  // namespace
