// Signed normal discrepancies (surface_discrepancy.h) against hand values on a plane, and PCL's
// scale-capable ICP row (PCL-ICP-S) recovering a known similarity on a curved grid.
#include <pcl_ls3d/evaluation/pcl_methods.h>
#include <pcl_ls3d/evaluation/registration_run.h>
#include <pcl_ls3d/evaluation/surface_discrepancy.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_ls3d::evaluation;

namespace {
/// 41 × 41 points with 0.5 m spacing on z = h(x, y).
template <typename F>
pcl::PointCloud<pcl::PointXYZ>::Ptr
grid(F h)
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr c(new pcl::PointCloud<pcl::PointXYZ>);
  for (int i = -20; i <= 20; ++i)
    for (int j = -20; j <= 20; ++j) {
      const double x = 0.5 * i, y = 0.5 * j;
      c->push_back(pcl::PointXYZ(static_cast<float>(x), static_cast<float>(y), static_cast<float>(h(x, y))));
    }
  return c;
}
}  // namespace

// A plane lifted by 0.1 m: every discrepancy is +0.1 along the upward normal (median 0.1,
// σ_MAD 0); at the identity they are 0; lowering gives −0.1; beyond the reach nothing counts.
TEST(SurfaceDiscrepancy, LiftedPlane)
{
  const auto plane = grid([](double x, double y) { return 0.1 * x - 0.05 * y; });
  const Eigen::Matrix3Xd points = cloudToMatrix(*plane);
  SurfaceDiscrepancy disc(plane);
  EXPECT_EQ(disc.flatPlanes(), plane->size());
  const DiscrepancyStats zero = disc.evaluate(points, Eigen::Matrix4d::Identity());
  EXPECT_EQ(zero.points, plane->size());
  EXPECT_NEAR(zero.median, 0.0, 1e-6);
  EXPECT_NEAR(zero.sigma_mad, 0.0, 1e-6);

  const Eigen::Vector3d n = Eigen::Vector3d(-0.1, 0.05, 1.0).normalized();
  Eigen::Matrix4d up = Eigen::Matrix4d::Identity();
  up.topRightCorner<3, 1>() = 0.1 * n;
  const DiscrepancyStats lifted = disc.evaluate(points, up);
  EXPECT_NEAR(lifted.median, 0.1, 1e-5);
  EXPECT_NEAR(lifted.sigma_mad, 0.0, 1e-5);
  EXPECT_NEAR(lifted.rms, 0.1, 1e-5);

  up.topRightCorner<3, 1>() = -0.1 * n;
  EXPECT_NEAR(disc.evaluate(points, up).median, -0.1, 1e-5);

  up.topRightCorner<3, 1>() = 2.0 * n;  // 2 m away: beyond the 1 m reach
  const DiscrepancyStats far = disc.evaluate(points, up);
  EXPECT_EQ(far.points, 0u);
  EXPECT_TRUE(std::isnan(far.sigma_mad));
}

// PCL's ICP with TransformationEstimationSVDScale recovers a 1 % scale with a small shift on a
// curved grid whose points correspond one to one; the rigid PCL-ICP cannot (scale stays 1).
TEST(SurfaceDiscrepancy, PclIcpWithScaleRow)
{
  const auto target = grid([](double x, double y) { return 0.5 * std::sin(0.4 * x) * std::cos(0.3 * y); });
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity();
  truth.topLeftCorner<3, 3>() *= 1.01;
  truth(0, 3) = 0.05;
  pcl::PointCloud<pcl::PointXYZ>::Ptr source(new pcl::PointCloud<pcl::PointXYZ>);
  const Eigen::Matrix4d inv = truth.inverse();
  for (const auto& p : *target) {
    const Eigen::Vector4d x = inv * Eigen::Vector4d(p.x, p.y, p.z, 1.0);
    source->push_back(
        pcl::PointXYZ(static_cast<float>(x.x()), static_cast<float>(x.y()), static_cast<float>(x.z())));
  }
  EXPECT_EQ(pclMethodName(PclMethod::ICP_SCALE), "PCL-ICP-S");
  const RegistrationRun scaled = runPclMethod(PclMethod::ICP_SCALE, source, target);
  ASSERT_TRUE(scaled.ran) << scaled.message;
  EXPECT_FALSE(scaled.stop.empty());
  const Eigen::Matrix3d scaled_r = scaled.transformation.topLeftCorner<3, 3>();
  EXPECT_NEAR(std::cbrt(scaled_r.determinant()), 1.01, 1e-4);
  const RegistrationRun rigid = runPclMethod(PclMethod::ICP, source, target);
  ASSERT_TRUE(rigid.ran) << rigid.message;
  const Eigen::Matrix3d rigid_r = rigid.transformation.topLeftCorner<3, 3>();
  EXPECT_NEAR(rigid_r.determinant(), 1.0, 1e-5);
}
