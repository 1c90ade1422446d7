// Displacement and parameter errors against hand-computed cases. Tolerances are 1e-12 (pure
// double arithmetic on values of order 1–100) unless stated.
#include <pcl_ls3d/evaluation/transform_error.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using pcl_ls3d::SimilarityTransform;
using pcl_ls3d::Vector7d;
using pcl_ls3d::evaluation::computeTransformError;
using pcl_ls3d::evaluation::displacementError;
using pcl_ls3d::evaluation::parameterErrors;

namespace {
Eigen::Matrix3Xd
points(std::initializer_list<Eigen::Vector3d> list)
{
  Eigen::Matrix3Xd P(3, static_cast<Eigen::Index>(list.size()));
  Eigen::Index i = 0;
  for (const auto& p : list)
    P.col(i++) = p;
  return P;
}
}  // namespace

// Same transform: every error is exactly zero.
TEST(TransformError, IdenticalTransformsGiveZero)
{
  SimilarityTransform s;
  s.t = Eigen::Vector3d(1, 2, 3);
  s.phi = 0.1;
  s.kappa = -0.2;
  s.m = 1.01;
  const auto e = computeTransformError(s.matrix(), s.matrix(), points({{1, 2, 3}, {-4, 5, 6}}));
  ASSERT_TRUE(e.valid);
  EXPECT_EQ(e.points, 2u);
  EXPECT_NEAR(e.mean, 0.0, 1e-12);
  EXPECT_NEAR(e.max, 0.0, 1e-12);
  EXPECT_NEAR(e.max_bbox, 0.0, 1e-12);
  EXPECT_NEAR(e.parameters.norm(), 0.0, 1e-12);
}

// A translation error of (0.3, 0, 0.4) displaces every point by exactly 0.5.
TEST(TransformError, TranslationOnly)
{
  Eigen::Matrix4d T_est = Eigen::Matrix4d::Identity();
  T_est.block<3, 1>(0, 3) = Eigen::Vector3d(0.3, 0.0, 0.4);
  const auto e =
      computeTransformError(T_est, Eigen::Matrix4d::Identity(), points({{0, 0, 0}, {10, 0, 0}, {0, 50, -7}}));
  ASSERT_TRUE(e.valid);
  EXPECT_NEAR(e.mean, 0.5, 1e-12);
  EXPECT_NEAR(e.rms, 0.5, 1e-12);
  EXPECT_NEAR(e.max, 0.5, 1e-12);
  EXPECT_NEAR(e.max_bbox, 0.5, 1e-12);
  EXPECT_NEAR(e.parameters[pcl_ls3d::TX], 0.3, 1e-12);
  EXPECT_NEAR(e.parameters[pcl_ls3d::TY], 0.0, 1e-12);
  EXPECT_NEAR(e.parameters[pcl_ls3d::TZ], 0.4, 1e-12);
  EXPECT_NEAR(e.parameters.tail<4>().norm(), 0.0, 1e-12);
}

// A κ error about the origin moves a point at radius r by the chord 2 r sin(κ/2).
TEST(TransformError, RotationAboutZ)
{
  SimilarityTransform est;
  est.kappa = 0.01;
  const double chord = 2.0 * std::sin(0.005);
  const auto P = points({{10, 0, 0}, {0, 20, 0}});
  const auto e = computeTransformError(est.matrix(), Eigen::Matrix4d::Identity(), P);
  ASSERT_TRUE(e.valid);
  EXPECT_NEAR(e.mean, 15.0 * chord, 1e-12);
  EXPECT_NEAR(e.rms, std::sqrt((100.0 + 400.0) / 2.0) * chord, 1e-12);
  EXPECT_NEAR(e.max, 20.0 * chord, 1e-12);
  // Bounding box [0,10]×[0,20]×[0,0]: the farthest corner is (10, 20, 0), r = √500.
  EXPECT_NEAR(e.max_bbox, std::sqrt(500.0) * chord, 1e-12);
  EXPECT_NEAR(e.parameters[pcl_ls3d::KAPPA], 0.01, 1e-12);
  EXPECT_NEAR(e.parameters[pcl_ls3d::PHI], 0.0, 1e-12);
  EXPECT_NEAR(e.parameters[pcl_ls3d::OMEGA], 0.0, 1e-12);
  EXPECT_NEAR(displacementError(est.matrix(), Eigen::Matrix4d::Identity(), {0, 20, 0}), 20.0 * chord, 1e-12);
}

// A scale error dm displaces x by dm·|x| (both transforms otherwise equal, about the origin).
TEST(TransformError, ScaleOnly)
{
  SimilarityTransform est, truth;
  truth.phi = 0.2;  // common rotation must not matter
  est.phi = 0.2;
  est.m = 1.001;
  const auto e = computeTransformError(est.matrix(), truth.matrix(), points({{3, 4, 0}, {0, 0, 100}}));
  ASSERT_TRUE(e.valid);
  EXPECT_NEAR(e.mean, 0.001 * (5.0 + 100.0) / 2.0, 1e-12);
  EXPECT_NEAR(e.max, 0.1, 1e-12);
  EXPECT_NEAR(e.parameters[pcl_ls3d::SCALE], 0.001, 1e-12);
  EXPECT_NEAR(e.parameters[pcl_ls3d::PHI], 0.0, 1e-12);
}

// κ = π − 0.01 against κ = −π + 0.01 is a 0.02 rad error, not 2π − 0.02.
TEST(TransformError, AngleDifferenceIsWrapped)
{
  SimilarityTransform est, truth;
  est.kappa = M_PI - 0.01;
  truth.kappa = -M_PI + 0.01;
  const Vector7d e = parameterErrors(est.matrix(), truth.matrix());
  EXPECT_NEAR(e[pcl_ls3d::KAPPA], -0.02, 1e-9);  // fromMatrix goes through atan2: ~1e-15
}

// Bad input: no points or a non-finite transform is invalid; a NaN point is skipped.
TEST(TransformError, InvalidInput)
{
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  EXPECT_FALSE(computeTransformError(I, I, Eigen::Matrix3Xd(3, 0)).valid);
  Eigen::Matrix4d bad = I;
  bad(0, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(computeTransformError(bad, I, points({{1, 1, 1}})).valid);

  Eigen::Matrix4d T = I;
  T(2, 3) = 0.25;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto e = computeTransformError(T, I, points({{nan, 0, 0}, {1, 2, 3}}));
  ASSERT_TRUE(e.valid);
  EXPECT_EQ(e.points, 1u);
  EXPECT_NEAR(e.mean, 0.25, 1e-12);
  EXPECT_FALSE(computeTransformError(T, I, points({{nan, 0, 0}})).valid);
}
