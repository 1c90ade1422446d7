/// \file test_segment_kinds.cpp
/// \brief The kind of a segment from its shape (segment_kinds.h), on constructed shapes.

#include <pcl_ls3d/segmentation/segment_kinds.h>

#include <gtest/gtest.h>

namespace sg = pcl_ls3d::segmentation;

namespace {

/// A segment of 200 points, none ground, with the given eigenvalues (ascending), normal and
/// median residual.
sg::SegmentShape
shape(const Eigen::Vector3d& lambda, const Eigen::Vector3d& normal, double residual)
{
  sg::SegmentShape s;
  s.n = 200;
  s.lambda = lambda;
  s.normal = normal;
  s.median_residual = residual;
  return s;
}

}  // namespace

// Roughness of the points makes vegetation only when the segment is not flat at its own
// scale: a facade with windows and recesses, or a gravel roof, has point residuals three times
// the ground's but is a sheet (√(λ3/λ2) = 0.02): a wall, a roof. A crown of the same point
// roughness is thick (√(λ3/λ2) = 0.5) and stays rough. 77050_627755's facades and
// 77060_627760's flat roof were rough before, so facades joined no roof and the roof joined
// the crowns beside it.
TEST(SegmentKinds, FlatSegmentsAreSurfacesHoweverRoughTheirPoints)
{
  const double ground = 0.01, rough = 0.03;  // point residuals: the ground's and 3 x it
  const sg::KindSettings k;
  const Eigen::Vector3d sheet(0.0004, 1.0, 4.0), thick(0.25, 1.0, 4.0);
  EXPECT_EQ(sg::kindOf(shape(sheet, Eigen::Vector3d::UnitX(), rough), ground, k), sg::SegmentKind::Wall);
  EXPECT_EQ(sg::kindOf(shape(sheet, Eigen::Vector3d::UnitZ(), rough), ground, k), sg::SegmentKind::Solid);
  EXPECT_EQ(sg::kindOf(shape(thick, Eigen::Vector3d::UnitZ(), rough), ground, k), sg::SegmentKind::Rough);
  // Smooth segments keep their kinds.
  EXPECT_EQ(sg::kindOf(shape(sheet, Eigen::Vector3d::UnitX(), ground), ground, k), sg::SegmentKind::Wall);
  EXPECT_EQ(sg::kindOf(shape(thick, Eigen::Vector3d::UnitZ(), ground), ground, k), sg::SegmentKind::Solid);
}
