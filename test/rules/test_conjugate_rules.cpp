// The shipped conjugate-point rules on an exactly known surface: a tilted plane sampled on a
// grid, z = 0.2 x − 0.1 y + 3, queried from the PCL-free PointVectorTargetSurface.
#include <pcl_ls3d/rules/icp_rule.h>
#include <pcl_ls3d/rules/lnd_rule.h>
#include <pcl_ls3d/rules/lzd_rule.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_ls3d;

namespace {
double
planeZ(double x, double y)
{
  return 0.2 * x - 0.1 * y + 3.0;
}

PointVectorTargetSurface
tiltedPlane()
{
  std::vector<Eigen::Vector3d> pts;
  for (int i = -10; i <= 10; ++i)
    for (int j = -10; j <= 10; ++j)
      pts.emplace_back(i, j, planeZ(i, j));
  return PointVectorTargetSurface(pts);
}
}  // namespace

TEST(ConjugateRules, LndGivesSignedNormalDistance)
{
  const auto target = tiltedPlane();
  const Eigen::Vector3d n = Eigen::Vector3d(-0.2, 0.1, 1.0).normalized();
  const Eigen::Vector3d q = Eigen::Vector3d(0.3, 0.4, planeZ(0.3, 0.4)) + 0.25 * n;
  LndRule rule;
  CorrespondenceCache cache;
  ConjugateObservations out;
  ASSERT_TRUE(rule.findConjugate(q, target, 10.0, cache, out));
  ASSERT_EQ(out.count, 1);
  EXPECT_NEAR(out.items[0].distance, 0.25, 1e-6);  // cached plane is float
  EXPECT_NEAR(out.items[0].direction.dot(n), 1.0, 1e-6);
  EXPECT_NEAR(out.items[0].foot.z(), planeZ(out.items[0].foot.x(), out.items[0].foot.y()), 1e-6);
  // Max distance enforced; outside the target's extent: no correspondence.
  ConjugateObservations none;
  CorrespondenceCache fresh;
  out.clear();
  EXPECT_FALSE(rule.findConjugate(q, target, 0.1, fresh, none));
  EXPECT_FALSE(rule.findConjugate(Eigen::Vector3d(14, 0, planeZ(14, 0)), target, 10.0, fresh, none));
}

TEST(ConjugateRules, LzdGivesHeightDifferenceWithSlopeGradient)
{
  const auto target = tiltedPlane();
  const Eigen::Vector3d q(1.3, -2.6, planeZ(1.3, -2.6) - 0.4);
  LzdRule rule;
  CorrespondenceCache cache;
  ConjugateObservations out;
  ASSERT_TRUE(rule.findConjugate(q, target, 10.0, cache, out));
  EXPECT_NEAR(out.items[0].distance, -0.4, 1e-6);
  // ∂l/∂x' = (−∂z/∂x, −∂z/∂y, 1)
  EXPECT_LT((out.items[0].direction - Eigen::Vector3d(-0.2, 0.1, 1.0)).norm(), 1e-6);
  EXPECT_NEAR(out.items[0].foot.x(), 1.3, 1e-12);
}

// ICP: three observations of x' − q (q the closest target point) along the local normal (unit
// weight) and two tangents (weight p_t < 1, as √p_t u): they reconstruct x' − q exactly.
TEST(ConjugateRules, IcpGivesThreeAxisObservations)
{
  const auto target = tiltedPlane();
  const Eigen::Vector3d q(2.1, 3.05, planeZ(2, 3) + 0.05);
  IcpRule rule;
  CorrespondenceCache cache;
  ConjugateObservations out;
  ASSERT_TRUE(rule.findConjugate(q, target, 10.0, cache, out));
  ASSERT_EQ(out.count, 3);
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const auto& o = out.items[static_cast<std::size_t>(k)];
    d += o.distance / o.direction.squaredNorm() * o.direction;
  }
  EXPECT_NEAR((d - Eigen::Vector3d(0.1, 0.05, 0.05)).norm(), 0.0, 1e-9);
  const Eigen::Vector3d normal = Eigen::Vector3d(-0.2, 0.1, 1.0).normalized();
  EXPECT_NEAR(std::abs(out.items[0].direction.dot(normal)), 1.0, 1e-9);
  EXPECT_LT(out.items[1].direction.norm(), 0.5);  // tangents discounted (noise-free plane)
  // Frozen: the same closest point is kept although the query moved next to another sample.
  cache.frozen = true;
  out.clear();
  ASSERT_TRUE(rule.findConjugate(Eigen::Vector3d(3.0, 3.0, planeZ(3, 3)), target, 10.0, cache, out));
  EXPECT_NEAR(out.items[0].distance, 0.0, 1e-6);  // on the plane through q (cached as float)
  EXPECT_NEAR(out.items[0].foot.x(), 2.0, 1e-6);
  CorrespondenceCache fresh;
  out.clear();
  EXPECT_FALSE(rule.findConjugate(Eigen::Vector3d(12, 0, planeZ(12, 0)), target, 10.0, fresh, out));
}

TEST(ConjugateRules, TriangleVariantsOnThePlane)
{
  const auto target = tiltedPlane();
  const Eigen::Vector3d q(1.3, -2.6, planeZ(1.3, -2.6) - 0.4);
  CorrespondenceCache c1, c2;
  ConjugateObservations o1, o2;
  ASSERT_TRUE(LzdRule(8, LzdRule::Surface::TRIANGLE).findConjugate(q, target, 10.0, c1, o1));
  EXPECT_NEAR(o1.items[0].distance, -0.4, 1e-9);
  ASSERT_TRUE(LndRule(8, LndRule::Surface::TRIANGLE).findConjugate(q, target, 10.0, c2, o2));
  EXPECT_NEAR(o2.items[0].distance, -0.4 / Eigen::Vector3d(-0.2, 0.1, 1.0).norm(), 1e-9);
  // Frozen with nothing cached: no correspondence (the observation set stays fixed).
  CorrespondenceCache frozen;
  frozen.frozen = true;
  ConjugateObservations o3;
  EXPECT_FALSE(LndRule().findConjugate(q, target, 10.0, frozen, o3));
}

TEST(ConjugateRules, FactoryAndParser)
{
  ConjugateRuleType t;
  ASSERT_TRUE(parseConjugateRuleType("LZD", t));
  EXPECT_EQ(makeConjugateRule(t)->name(), "LZD");
  EXPECT_FALSE(parseConjugateRuleType("nearest", t));
}
