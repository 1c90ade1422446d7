// The choice between MM's starts: at 42 % of Li's surface deformed by 5 σ the MM fit ends 3–7 σ
// off (its M-step or its LTS start compromises between the stable and the moved part), the fit
// from the block start reaches the truth and is chosen by its smaller stable-part scatter. The
// scatter itself: ≈ σ at the truth, larger at the compromise, infinite when the regions cover
// more than half of the surface. Other estimators make no choice.
#include "deformation/li_surface_pair.h"

#include <pcl_ls3d/deformation/deformation_analysis.h>
#include <pcl_ls3d/deformation/start_choice.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_ls3d;
using namespace pcl_ls3d::deformation;
using li_test::liSurface;

namespace {

constexpr double kSigma = 20.0;

struct LiPair : li_test::LiSurfacePair
{
  using LiSurfacePair::LiSurfacePair;
  DeformationResult
  run(bool block_start) const
  {
    DeformationSettings s;
    s.matching.mm_block_start = block_start;
    return analyseDeformation(points, *surface, *rule, s);
  }
  double
  scatter(const AdjustmentReport& fit, double noise) const
  {
    DeformationSettings s;
    s.regions.plane_axis = 2;  // as the analysis does for LZD
    return stablePartScatter(points, *surface, *rule, fit, noise, s.residuals, s.regions);
  }
};

}  // namespace

TEST(StartChoice, BlockStartRescuesTheCompromise)
{
  const std::pair<synth::DeformationPosition, std::uint32_t> cases[] = {
      {synth::DeformationPosition::LOWER_RIGHT, 2u}, {synth::DeformationPosition::MIDDLE, 2u}};
  for (const auto& c : cases) {
    const LiPair pair(liSurface(42.0, 5.0, c.first, c.second));
    const DeformationResult mm = pair.run(false);
    ASSERT_TRUE(mm.ok()) << mm.matching.message;
    EXPECT_GT(pair.errorSigma(mm.matching.adjustment.transformation), 2.0) << "seed " << c.second << ": MM no longer compromises";
    EXPECT_TRUE(mm.start_choice.candidates.empty());
    const DeformationResult chosen = pair.run(true);
    ASSERT_TRUE(chosen.ok()) << chosen.matching.message;
    EXPECT_LT(pair.errorSigma(chosen.matching.adjustment.transformation), 0.5) << "seed " << c.second;
    EXPECT_LT(pair.errorSigma(chosen.matching.block_start_transformation), 1.0);
    EXPECT_GT(chosen.matching.block_support, 0.3);
    ASSERT_EQ(chosen.start_choice.candidates.size(), 3u);
    EXPECT_EQ(chosen.start_choice.chosen, "block start");
    EXPECT_NE(chosen.matching.estimator.find("block start"), std::string::npos);
    // The chosen candidate scored strictly less than the MM fit, and about σ.
    const StartCandidate& mm_score = chosen.start_choice.candidates[0];
    const StartCandidate& block_score = chosen.start_choice.candidates[2];
    EXPECT_EQ(mm_score.name, "mm");
    EXPECT_LT(block_score.scatter, mm_score.scatter);
    EXPECT_GT(block_score.scatter, 0.85 * kSigma);
    EXPECT_LT(block_score.scatter, 1.2 * kSigma);
  }
}

TEST(StartChoice, ScatterIsTheNoiseAtTheTruthAndLargerAtACompromise)
{
  const LiPair pair(liSurface(42.0, 5.0, synth::DeformationPosition::LOWER_RIGHT, 2));
  const DeformationResult compromise = pair.run(false);
  const DeformationResult truth_like = pair.run(true);
  ASSERT_TRUE(compromise.ok() && truth_like.ok());
  const double noise = truth_like.matching.neighbour_noise;
  ASSERT_GT(noise, 0.0);
  const double at_truth = pair.scatter(truth_like.matching.adjustment, noise);
  const double at_compromise = pair.scatter(compromise.matching.adjustment, noise);
  EXPECT_GT(at_truth, 0.85 * kSigma);
  EXPECT_LT(at_truth, 1.2 * kSigma);
  EXPECT_GT(at_compromise, 1.15 * at_truth);
  // Everything 10 σ off: every point is significant, no stable half is left.
  AdjustmentReport lifted = truth_like.matching.adjustment;
  lifted.parameters[2] += 10.0 * kSigma;
  EXPECT_TRUE(std::isinf(pair.scatter(lifted, noise)));
}

TEST(StartChoice, OnlyMmChoosesAndAnUndeformedSurfaceKeepsItsFit)
{
  const LiPair deformed(liSurface(25.0, 10.0, synth::DeformationPosition::UPPER_LEFT));
  DeformationSettings lms;
  lms.matching.method = RobustMethod::LMS;
  const DeformationResult r = analyseDeformation(deformed.points, *deformed.surface, *deformed.rule, lms);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r.start_choice.candidates.empty());
  EXPECT_EQ(r.matching.block_support, 0.0);
  const LiPair flat(liSurface(0.0, 0.0, synth::DeformationPosition::MIDDLE));
  const DeformationResult f = flat.run(true);
  ASSERT_TRUE(f.ok());
  EXPECT_LT(flat.errorSigma(f.matching.adjustment.transformation), 0.3);
  ASSERT_EQ(f.start_choice.candidates.size(), 3u);
  EXPECT_EQ(f.start_choice.chosen, "mm");  // the three agree within the MAD's standard error
  for (const StartCandidate& c : f.start_choice.candidates) {
    EXPECT_TRUE(c.usable) << c.name;
    EXPECT_LT(c.scatter, 1.2 * kSigma) << c.name;
  }
}
