// Checks the one rotation convention the whole library shares, against an independent
// construction from elementary rotation matrices.
#include <pcl_ls3d/common/similarity_transform.h>

#include <gtest/gtest.h>

#include <cmath>

using pcl_ls3d::SimilarityTransform;

namespace {
Eigen::Matrix3d
rotX(double a)
{
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return R;
}
Eigen::Matrix3d
rotY(double a)
{
  Eigen::Matrix3d R;
  R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return R;
}
Eigen::Matrix3d
rotZ(double a)
{
  Eigen::Matrix3d R;
  R << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return R;
}
}  // namespace

TEST(SimilarityTransform, RotationIsYXZProductOfElementaryRotations)
{
  SimilarityTransform s;
  s.phi = 0.3;
  s.omega = -0.2;
  s.kappa = 1.1;
  EXPECT_TRUE(s.rotation().isApprox(rotY(0.3) * rotX(-0.2) * rotZ(1.1), 1e-14));
}

TEST(SimilarityTransform, MatrixRoundTripRecoversAllSevenParameters)
{
  pcl_ls3d::Vector7d p;
  p << 12.5, -3.25, 0.75, 0.01, -0.02, 2.5, 1.0003;
  const SimilarityTransform s(p);
  const SimilarityTransform back = SimilarityTransform::fromMatrix(s.matrix());
  for (int i = 0; i < 7; ++i)
    EXPECT_NEAR(back.vector()[i], p[i], 1e-12) << pcl_ls3d::similarityParameterNames()[i];
}

TEST(SimilarityTransform, InverseUndoesApply)
{
  pcl_ls3d::Vector7d p;
  p << 1, 2, 3, 0.1, 0.2, -0.3, 0.98;
  const SimilarityTransform s(p);
  const Eigen::Vector3d x(10.0, -4.0, 7.5);
  EXPECT_TRUE(s.inverse().apply(s.apply(x)).isApprox(x, 1e-12));
  EXPECT_TRUE(s.apply(x).isApprox(s.matrix().topLeftCorner<3, 3>() * x + s.t, 1e-12));
}

TEST(SimilarityTransform, LocalGlobalConversionMapsTheSamePoints)
{
  pcl_ls3d::Vector7d p;
  p << 0.5, -0.2, 0.1, 0.001, 0.002, 0.003, 1.0001;
  const Eigen::Matrix4d T_local = SimilarityTransform(p).matrix();
  const Eigen::Vector3d os(500000.0, 5000000.0, 100.0), ot(500010.0, 4999990.0, 90.0);
  const Eigen::Matrix4d T_global = pcl_ls3d::localToGlobal(T_local, os, ot);
  const Eigen::Vector3d x_local(12.0, -7.0, 3.0);
  const Eigen::Vector3d y_local = (T_local * x_local.homogeneous()).head<3>();
  const Eigen::Vector3d y_global = (T_global * (x_local + os).homogeneous()).head<3>();
  EXPECT_LT((y_global - (y_local + ot)).norm(), 1e-6);
  // Absolute tolerance: the round trip passes through translations of 5e6 m.
  EXPECT_LT((pcl_ls3d::globalToLocal(T_global, os, ot) - T_local).cwiseAbs().maxCoeff(), 1e-8);
}
