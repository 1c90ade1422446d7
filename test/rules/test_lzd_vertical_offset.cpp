// LZD observes along z: a point far above a steep slope (a deformation several point spacings
// high) still gets its conjugate vertically below it, not an element on the nearest hillside.
// The 3-D nearest neighbours of such a point lie one-sided around the slope's foot point; the
// rule re-centres its search at the height found first.
#include <pcl_ls3d/rules/lzd_rule.h>

#include <gtest/gtest.h>

using namespace pcl_ls3d;

namespace {
double
slopeZ(double x, double y)
{
  return 3.0 * x + 0.5 * y + 0.01 * x * x;  // steep (71°) and gently curved
}
}  // namespace

TEST(LzdVerticalOffset, PointFarAboveSteepSlopeGetsVerticalConjugate)
{
  std::vector<Eigen::Vector3d> pts;
  for (int i = -20; i <= 20; ++i)
    for (int j = -20; j <= 20; ++j)
      pts.emplace_back(i, j, slopeZ(i, j));
  const PointVectorTargetSurface target(pts);
  LzdRule rule;
  for (const double offset : {-15.0, 0.4, 15.0, 40.0}) {
    const Eigen::Vector3d q(0.3, -0.2, slopeZ(0.3, -0.2) + offset);
    CorrespondenceCache cache;
    ConjugateObservations out;
    ASSERT_TRUE(rule.findConjugate(q, target, 1e9, cache, out)) << "offset " << offset;
    ASSERT_EQ(out.count, 1);
    EXPECT_NEAR(out.items[0].distance, offset, 1e-3) << "offset " << offset;
    EXPECT_NEAR(out.items[0].foot.x(), 0.3, 1e-12);
    EXPECT_NEAR(out.items[0].foot.y(), -0.2, 1e-12);
    EXPECT_NEAR(out.items[0].direction.x(), -(3.0 + 0.02 * 0.3), 1e-3);  // (−∂z/∂x, −∂z/∂y, 1)
    EXPECT_NEAR(out.items[0].direction.y(), -0.5, 1e-3);
  }
}
