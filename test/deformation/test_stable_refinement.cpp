// Stable-part refinement: the deformed regions and their rim are left out and the rest matched
// again. nearRegions() against a brute-force count; on Li's surface, a small deformation that
// pulls the robust estimators beyond 0.5 σ at the far corner is recovered once its region is
// left out, and a surface without deformation is not touched.
#include "deformation/li_surface_pair.h"

#include <pcl_ls3d/deformation/deformation_analysis.h>
#include <pcl_ls3d/deformation/stable_refinement.h>
#include <pcl_ls3d/evaluation/transform_error.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/synth/li_surface.h>

#include <pcl/search/kdtree.h>

#include <gtest/gtest.h>

#include <utility>

using namespace pcl_ls3d;
using namespace pcl_ls3d::deformation;

namespace {

constexpr double kSigma = 20.0;

// A 20 × 20 grid of spacing 1; the 4 × 4 block at (5..8, 5..8) is region 1 and lies 100 above.
struct GridWithRegion
{
  GridWithRegion()
  {
    analysis.adjacency = 1.5;
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 20; ++x) {
        const bool in = x >= 5 && x <= 8 && y >= 5 && y <= 8;
        points.emplace_back(x, y, in ? 100.0 : 0.0);
        analysis.region.push_back(in ? 1 : 0);
      }
  }
  std::vector<Eigen::Vector3d> points;
  RegionAnalysis analysis;
};

}  // namespace

TEST(StableRefinement, NearRegionsIsTheRegionAndItsRimInPlan)
{
  const GridWithRegion g;
  const std::vector<std::uint8_t> left = nearRegions(g.points, g.analysis, 2);
  ASSERT_EQ(left.size(), g.points.size());
  for (std::size_t i = 0; i < g.points.size(); ++i) {
    bool near = false;  // brute force, in plan
    for (std::size_t j = 0; j < g.points.size(); ++j)
      near = near || (g.analysis.region[j] > 0 && (g.points[i] - g.points[j]).head<2>().norm() <= 1.5);
    EXPECT_EQ(left[i] != 0, near) << "point " << i;
  }
  // The block (16) and its rim of one node, diagonals included: 6 × 6.
  EXPECT_EQ(std::count(left.begin(), left.end(), 1), 36);
}

TEST(StableRefinement, NearRegionsIn3dKeepsTheGroundBelowARaisedRegion)
{
  const GridWithRegion g;
  const std::vector<std::uint8_t> left = nearRegions(g.points, g.analysis, -1);
  EXPECT_EQ(std::count(left.begin(), left.end(), 1), 16);  // 100 above: no neighbour in 3-D
}

TEST(StableRefinement, InvalidSettingsAreRefused)
{
  StableRefinementSettings s;
  EXPECT_TRUE(s.isValid());
  s.max_rounds = -1;
  std::string why;
  EXPECT_FALSE(s.isValid(&why));
  EXPECT_FALSE(why.empty());
  s.max_rounds = 2;
  s.max_left_out = 0.0;
  EXPECT_FALSE(s.isValid());
  DeformationSettings d;
  d.refinement.max_left_out = 1.5;
  EXPECT_FALSE(d.isValid());
}

namespace {

struct LiCase : li_test::LiSurfacePair
{
  LiCase(double percent, double c, synth::DeformationPosition position, std::uint32_t seed)
      : LiSurfacePair(li_test::liSurface(percent, c, position, seed))
  {}
  DeformationResult
  run(int rounds, bool hold_out = true) const
  {
    DeformationSettings s;
    s.refinement.max_rounds = rounds;
    s.matching.mm_hold_out_beyond_start = hold_out;
    return analyseDeformation(points, *surface, *rule, s);
  }
  double
  errorSigma(const DeformationResult& r) const
  {
    return LiSurfacePair::errorSigma(r.matching.adjustment.transformation);
  }
};

}  // namespace

// 9 % of the surface at the upper-left corner raised by only N(3σ, σ): the MM estimate is pulled
// more than 0.5 σ at the far corner (Tukey still weighs a 3 σ residual 0.35), and its residuals
// show the patch at about half its height; leaving the patch out recovers the truth.
TEST(StableRefinement, SmallDeformationAtACornerIsLeftOut)
{
  for (std::uint32_t seed : {1u, 2u}) {
    const LiCase c(9.0, 3.0, synth::DeformationPosition::UPPER_LEFT, seed);
    const DeformationResult alone = c.run(0);
    ASSERT_TRUE(alone.ok()) << alone.matching.message;
    EXPECT_EQ(alone.refinement.rounds, 0);
    EXPECT_GT(c.errorSigma(alone), 0.5) << "seed " << seed << ": the case no longer tests the refinement";
    const DeformationResult refined = c.run(10);
    ASSERT_TRUE(refined.ok()) << refined.matching.message;
    EXPECT_GE(refined.refinement.rounds, 1);
    EXPECT_LT(c.errorSigma(refined), 0.5) << "seed " << seed;
    // What was left out is about the patch (9 % of 2500 nodes) and its rim, not the surface.
    EXPECT_GT(refined.refinement.left_out, 150u);
    EXPECT_LT(refined.refinement.left_out, 600u);
    EXPECT_NE(refined.matching.estimator.find("stable part"), std::string::npos);
    EXPECT_NEAR(refined.matching.scale, kSigma, 0.15 * kSigma);
  }
}

// Without deformation the refinement changes nothing that matters: the answer stays the truth.
TEST(StableRefinement, NoDeformationStaysTheTruth)
{
  const LiCase c(0.0, 0.0, synth::DeformationPosition::MIDDLE, 2);
  const DeformationResult r = c.run(10);
  ASSERT_TRUE(r.ok()) << r.matching.message;
  EXPECT_LT(c.errorSigma(r), 0.25);
  EXPECT_LT(r.refinement.left_out, 250u);  // the neighbourhood means' false alarms, at most 10 %
}

// 36 % raised by N(5σ, σ): the MM fit (its M-step over every point, without the hold-out that
// now keeps most such fits near their start) is tilted towards the patch by 3–4 σ, and both the
// neighbourhood means and the point-wise test then flag more than half of the surface (the
// patch and the far side of the stable part). Leaving out the largest regions that stay within
// half lets the next round correct the tilt (before: no round, "the regions cover more than 50 %").
TEST(StableRefinement, TiltedFitLeavesOutItsLargestRegions)
{
  const std::pair<synth::DeformationPosition, std::uint32_t> cases[] = {
      {synth::DeformationPosition::UPPER_RIGHT, 1u}, {synth::DeformationPosition::LOWER, 1u}};
  for (const auto& k : cases) {
    const LiCase c(36.0, 5.0, k.first, k.second);
    const DeformationResult alone = c.run(0, false);
    ASSERT_TRUE(alone.ok()) << alone.matching.message;
    EXPECT_GT(c.errorSigma(alone), 1.0) << "the case no longer has a tilted robust fit";
    const DeformationResult refined = c.run(10, false);
    ASSERT_TRUE(refined.ok()) << refined.matching.message;
    EXPECT_GE(refined.refinement.rounds, 1) << refined.refinement.stopped;
    EXPECT_LT(c.errorSigma(refined), 0.5) << refined.refinement.stopped;
    EXPECT_LT(static_cast<double>(refined.refinement.left_out), 0.5 * 2500.0);
  }
}
