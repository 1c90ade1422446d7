// The choice between the starts of MM and LMS: at 42 % of Li's surface deformed by 5 σ the MM fit ends 3–7 σ
// off (its M-step or its LTS start compromises between the stable and the moved part), the fit
// from the block start reaches the truth and is chosen by its smaller stable-part scatter. The
// scatter itself: ≈ σ at the truth, larger at the compromise, infinite when the regions'
// significant points are half of the surface or more. At 49 % LMS's refused fit is replaced. Other estimators make no
// choice.
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
    s.matching.block_start = block_start;
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
    EXPECT_GT(pair.errorSigma(mm.matching.adjustment.transformation), 2.0)
        << "seed " << c.second << ": MM no longer compromises";
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

TEST(StartChoice, LmsAndMmChooseOthersDoNotAndAnUndeformedSurfaceKeepsItsFit)
{
  const LiPair deformed(liSurface(25.0, 10.0, synth::DeformationPosition::UPPER_LEFT));
  DeformationSettings md;
  md.matching.method = RobustMethod::MD;
  const DeformationResult r = analyseDeformation(deformed.points, *deformed.surface, *deformed.rule, md);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r.start_choice.candidates.empty());
  EXPECT_EQ(r.matching.block_support, 0.0);
  DeformationSettings lms;
  lms.matching.method = RobustMethod::LMS;
  const DeformationResult l = analyseDeformation(deformed.points, *deformed.surface, *deformed.rule, lms);
  ASSERT_TRUE(l.ok());
  ASSERT_EQ(l.start_choice.candidates.size(), 3u);
  EXPECT_EQ(l.start_choice.candidates[0].name, "lms");
  EXPECT_EQ(l.start_choice.candidates[1].name, "lms start");
  EXPECT_LT(deformed.errorSigma(l.matching.adjustment.transformation), 0.5);
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

// 49 % of the surface raised by 25 σ: LMS's M-step rejects the patch and the stable part's noise
// tail, more than half, and the quality gate refuses its fit; the fit from another start is
// scored and kept.
TEST(StartChoice, LmsFitRefusedAt49PercentIsReplacedByAnotherStart)
{
  const LiPair pair(liSurface(49.0, 25.0, synth::DeformationPosition::LOWER_LEFT, 4));
  DeformationSettings s;
  s.matching.method = RobustMethod::LMS;
  s.matching.block_start = false;
  const DeformationResult alone = analyseDeformation(pair.points, *pair.surface, *pair.rule, s);
  EXPECT_FALSE(alone.ok()) << "LMS alone is no longer refused here";
  EXPECT_TRUE(alone.start_choice.candidates.empty());
  s.matching.block_start = true;
  const DeformationResult chosen = analyseDeformation(pair.points, *pair.surface, *pair.rule, s);
  ASSERT_TRUE(chosen.ok()) << chosen.matching.message;
  EXPECT_LT(pair.errorSigma(chosen.matching.adjustment.transformation), 0.5);
  ASSERT_EQ(chosen.start_choice.candidates.size(), 3u);
  EXPECT_FALSE(chosen.start_choice.candidates[0].usable);  // the refused LMS fit
  EXPECT_TRUE(std::isinf(chosen.start_choice.candidates[0].scatter));
  EXPECT_NE(chosen.start_choice.chosen, "lms");
  EXPECT_NE(chosen.matching.estimator.find("chosen: the fit from its"), std::string::npos);
  EXPECT_NE(chosen.matching.estimator.find("own fit refused"), std::string::npos);
  // Without the refinement no start is refitted: the refused fit stays refused.
  s.refinement.max_rounds = 0;
  const DeformationResult unrefined = analyseDeformation(pair.points, *pair.surface, *pair.rule, s);
  EXPECT_FALSE(unrefined.ok());
  EXPECT_TRUE(unrefined.start_choice.candidates.empty());
  EXPECT_TRUE(unrefined.field.residual.empty());
}

// The majority test counts the significant points of the regions, not the stable points the
// hysteresis grew in: at 49 % deformed a weak growth threshold takes most of the rim, the
// grown regions cover more than half, and the right fit still scores its noise.
TEST(StartChoice, PointsGrownByHysteresisDoNotDecideTheMajority)
{
  const LiPair pair(liSurface(49.0, 25.0, synth::DeformationPosition::LOWER, 1));
  const DeformationResult r = pair.run(true);
  ASSERT_TRUE(r.ok()) << r.matching.message;
  ASSERT_LT(pair.errorSigma(r.matching.adjustment.transformation), 0.5);
  const double noise = r.matching.neighbour_noise;
  DeformationSettings s;
  s.regions.plane_axis = 2;
  s.regions.grow_k = 0.5;
  const ResidualField field =
      computeResidualField(pair.points, *pair.surface, *pair.rule, r.matching.adjustment, noise, s.residuals);
  const RegionAnalysis grown = analyseRegions(pair.points, field, s.regions);
  std::size_t in_regions = 0;
  for (int id : grown.region)
    in_regions += id > 0 ? 1 : 0;
  ASSERT_GT(2 * in_regions, field.observed);  // the grown regions alone would refuse the fit
  const double scatter = stablePartScatter(pair.points, *pair.surface, *pair.rule, r.matching.adjustment,
                                           noise, s.residuals, s.regions);
  EXPECT_TRUE(std::isfinite(scatter));
  EXPECT_LT(scatter, 1.2 * kSigma);
}
