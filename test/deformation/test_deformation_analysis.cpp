// Deformation detection on Li's surface with a planted deformation of known extent: the residual
// field's significance mask and its regions recover the patch; no deformation gives ~0 % area.
#include "deformation/li_surface_pair.h"

#include <pcl_ls3d/deformation/deformation_analysis.h>
#include <pcl_ls3d/deformation/deformation_map.h>
#include <pcl_ls3d/evaluation/transform_error.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/synth/li_surface.h>

#include <pcl/search/kdtree.h>

#include <gtest/gtest.h>

#include <limits>
#include <utility>

using namespace pcl_ls3d;
using li_test::liSurface;
using namespace pcl_ls3d::deformation;

namespace {

constexpr double kSigma = 20.0;

struct LiPair : li_test::LiSurfacePair
{
  using LiSurfacePair::LiSurfacePair;
  DeformationResult
  run(const DeformationSettings& s) const
  {
    return analyseDeformation(points, *surface, *rule, s);
  }
};

/// 200 × 200 nodes at `spacing` (the large, dense epochs of the 1 M-point pipeline in small),
/// 20 % raised by the default N(10σ, σ), Table 4's transform.
synth::LiSurface
denseGrid(double spacing, synth::DeformationPosition position)
{
  synth::LiSurfaceSettings s;
  s.grid_size = 200;
  s.spacing = spacing;
  s.deformation_percent = 20.0;
  s.position = position;
  return synth::makeLiSurface(s);
}

struct Detection
{
  double precision = 0.0, recall = 0.0;
};

/// Precision and recall of "in a region" (noise clusters excluded) against the planted patch,
/// over the points that have a residual (LZD gives none to a point beside the reference's border,
/// one-sided and off any sample).
Detection
score(const DeformationResult& r, const synth::LiSurface& li)
{
  std::size_t tp = 0, fp = 0, fn = 0;
  for (std::size_t i = 0; i < li.deformed.size(); ++i) {
    if (!std::isfinite(r.field.residual[i]))
      continue;
    const bool found = r.regions.region[i] > 0;
    tp += found && li.deformed[i];
    fp += found && !li.deformed[i];
    fn += !found && li.deformed[i];
  }
  Detection d;
  d.precision = tp + fp > 0 ? static_cast<double>(tp) / static_cast<double>(tp + fp) : 1.0;
  d.recall = tp + fn > 0 ? static_cast<double>(tp) / static_cast<double>(tp + fn) : 1.0;
  return d;
}

}  // namespace

// 16 % of the surface raised by N(10σ, σ) at a corner: the truth is recovered, the mask and its
// regions find the patch (one region, uplift, mean displacement ≈ 10 σ).
TEST(DeformationAnalysis, MaskRecoversPlantedPatch)
{
  const synth::LiSurface li = liSurface(16.0, 10.0, synth::DeformationPosition::UPPER_LEFT);
  const LiPair pair(li);
  const DeformationResult r = pair.run(DeformationSettings());
  ASSERT_TRUE(r.ok()) << r.matching.message;
  EXPECT_LT(pair.errorSigma(r.matching.adjustment.transformation), 0.5);
  ASSERT_EQ(r.field.residual.size(), li.mate->size());
  ASSERT_EQ(r.regions.region.size(), li.mate->size());
  const Detection d = score(r, li);
  EXPECT_GE(d.precision, 0.95);
  EXPECT_GE(d.recall, 0.9);
  ASSERT_FALSE(r.regions.regions.empty());
  const DeformationRegion& top = r.regions.regions.front();
  EXPECT_EQ(top.sign, 1);
  EXPECT_NEAR(top.mean, 10.0 * kSigma, 1.0 * kSigma);
  EXPECT_GT(top.volume, 0.0);
  // The area share is that of the patch (16 % of the nodes; the grid is regular).
  EXPECT_NEAR(r.regions.percent_deformed, li.percent, 2.0);
  // σ_i is of the order of the noise, residuals of stable nodes are centred on 0.
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < li.deformed.size(); ++i)
    if (!li.deformed[i] && std::isfinite(r.field.residual[i])) {
      sum += r.field.residual[i];
      ++n;
      EXPECT_GT(r.field.sigma[i], 0.5 * kSigma);
      EXPECT_LT(r.field.sigma[i], 2.0 * kSigma);
    }
  ASSERT_GT(n, 1500u);
  EXPECT_NEAR(sum / static_cast<double>(n), 0.0, 0.2 * kSigma);
}

// The M3C2-style level of detection finds the same patch. It tests the mean of the 12 nearest
// residuals, so the ring of stable nodes next to the patch is flagged too (their neighbourhood
// mean is pulled up): recall as high as the k·σ mask, lower precision (0.87 on this case).
TEST(DeformationAnalysis, LevelOfDetectionAlternative)
{
  const synth::LiSurface li = liSurface(9.0, 10.0, synth::DeformationPosition::MIDDLE, 3);
  const LiPair pair(li);
  DeformationSettings s;
  s.residuals.rule = DetectionRule::LOD95;
  const DeformationResult r = pair.run(s);
  ASSERT_TRUE(r.ok()) << r.matching.message;
  const Detection d = score(r, li);
  EXPECT_GE(d.precision, 0.75);
  EXPECT_GE(d.recall, 0.9);
}

// Without deformation: about 0 % of the area changed, and the least-squares answer.
TEST(DeformationAnalysis, NoDeformationGivesNoArea)
{
  const synth::LiSurface li = liSurface(0.0, 0.0, synth::DeformationPosition::MIDDLE, 2);
  const LiPair pair(li);
  const DeformationResult r = pair.run(DeformationSettings());
  ASSERT_TRUE(r.ok()) << r.matching.message;
  EXPECT_LT(pair.errorSigma(r.matching.adjustment.transformation), 0.25);
  EXPECT_LT(r.regions.percent_deformed, 0.5);
  EXPECT_TRUE(r.regions.regions.empty());
  // Isolated 3σ exceedances (0.27 % of the nodes expected) are noise, not regions.
  EXPECT_LT(r.field.significant_count, 25u);
}

// Bad input: stated results, no crash.
TEST(DeformationAnalysis, BadInput)
{
  const synth::LiSurface li = liSurface(9.0, 10.0, synth::DeformationPosition::MIDDLE);
  LiPair pair(li);
  DeformationSettings bad;
  bad.residuals.k = -1.0;
  const DeformationResult invalid = pair.run(bad);
  EXPECT_FALSE(invalid.ok());
  EXPECT_EQ(invalid.matching.termination, TerminationType::INVALID_INPUT);
  EXPECT_NE(invalid.matching.message.find("k"), std::string::npos);
  // All points NaN.
  LiPair nan_pair(li);
  for (auto& p : nan_pair.points)
    p = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  const DeformationResult none = nan_pair.run(DeformationSettings());
  EXPECT_FALSE(none.ok());
  EXPECT_FALSE(none.matching.message.empty());
  // Some NaN points: no residual for them, the rest as usual.
  const DeformationResult all = pair.run(DeformationSettings());
  ASSERT_TRUE(all.ok());
  ASSERT_TRUE(std::isfinite(all.field.residual[1275]));  // an inner node
  LiPair some_nan(li);
  some_nan.points[1275] = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  const DeformationResult some = some_nan.run(DeformationSettings());
  ASSERT_TRUE(some.ok()) << some.matching.message;
  EXPECT_TRUE(std::isnan(some.field.residual[1275]));
  EXPECT_EQ(some.regions.region[1275], 0);
  EXPECT_EQ(some.field.observed, all.field.observed - 1);
}

// Hysteresis (RegionSettings::grow_k): a patch raised by only N(5σ, σ) loses its low tail to
// the 3σ test; grown from the significant regions into adjacent points beyond 2σ, the regions
// take back most of it, and only points next to a region join (precision stays, isolated
// weak points stay out: the no-deformation surface gains nothing).
TEST(DeformationAnalysis, HysteresisRecoversTheLowTail)
{
  const synth::LiSurface li = liSurface(16.0, 5.0, synth::DeformationPosition::MIDDLE, 4);
  const LiPair pair(li);
  const DeformationResult r = pair.run(DeformationSettings());
  ASSERT_TRUE(r.ok()) << r.matching.message;
  ASSERT_LT(pair.errorSigma(r.matching.adjustment.transformation), 0.5);
  RegionSettings grow;
  grow.grow_k = 2.0;
  grow.plane_axis = r.regions.plane_normal_axis;  // as analyseDeformation() set it (LZD: xy)
  RegionSettings no_growth = grow;
  no_growth.grow_k = 0.0;
  DeformationResult grown = r, plain_regions = r;
  grown.regions = analyseRegions(pair.points, r.field, grow);
  plain_regions.regions = analyseRegions(pair.points, r.field, no_growth);
  const Detection g = score(grown, li), plain = score(plain_regions, li);
  EXPECT_LT(1.0 - g.recall, 0.5 * (1.0 - plain.recall));  // more than half the missed tail back
  EXPECT_GE(g.recall, 0.9);
  EXPECT_GE(g.precision, 0.95);
  EXPECT_EQ(grown.regions.regions.size(), plain_regions.regions.regions.size());  // grown, not new
  EXPECT_EQ(r.regions.region, grown.regions.region);  // growth at 2σ is the default

  const synth::LiSurface flat = liSurface(0.0, 0.0, synth::DeformationPosition::MIDDLE, 2);
  const LiPair none(flat);
  const DeformationResult n = none.run(DeformationSettings());
  ASSERT_TRUE(n.ok());
  EXPECT_TRUE(analyseRegions(none.points, n.field, grow).regions.empty());
  RegionSettings bad;
  bad.grow_k = -1.0;
  EXPECT_FALSE(bad.isValid());
}

// A large gridded epoch (the 1 M-point pipeline of issue 9 in small, 200 × 200 nodes at 25-unit
// spacing, 20 % raised by N(10σ, σ)).
// 1. The matching sample (DeformationSettings::matching_points = 1 in 20 nodes): every k-th node
//    would lie on lines whose neighbourhoods are collinear; the quality gate then measured the
//    epoch's noise as 0 and refused the right answer as UNRELIABLE (σ0 ≈ σ was "3.2e3 × the
//    surfaces' noise"). A random sample covers the surface in two directions: trusted, σ0 ≈ σ.
// 2. The whole patch is found (17.1 % of 20 % before LZD's re-centring was fixed).
TEST(DeformationAnalysis, GridEpochSampleIsNotAliased)
{
  const synth::LiSurface li =
      denseGrid(25.0, synth::DeformationPosition::UPPER_LEFT);  // the same 5000-unit extent
  const LiPair pair(li);
  DeformationSettings settings;
  settings.matching_points = 2000;  // 1 in 20 nodes
  const DeformationResult r = pair.run(settings);
  ASSERT_TRUE(r.ok()) << r.matching.message;
  EXPECT_EQ(r.matching.termination, TerminationType::CONVERGED) << r.matching.message;
  EXPECT_EQ(r.matching.start.source_points, 2000u);  // the sample (the final fit: its stable part)
  EXPECT_LT(pair.errorSigma(r.matching.adjustment.transformation), 0.5);
  EXPECT_NEAR(r.matching.adjustment.sigma0, kSigma, 0.25 * kSigma);
  // The deformed part is observed: LZD re-centres its search at the surface below a point 8
  // spacings above it (82 % of the deformed nodes had a residual before).
  std::size_t observed = 0;
  for (std::size_t i = 0; i < li.deformed.size(); ++i)
    observed += li.deformed[i] && std::isfinite(r.field.residual[i]);
  EXPECT_GT(static_cast<double>(observed), 0.97 * static_cast<double>(li.deformed_indices.size()));
  EXPECT_NEAR(r.regions.percent_deformed, li.percent, 2.0);
}

// A surface sampled more densely than its noise (8-unit grid, σ = 20; the 1 M-point pipeline
// has 5): in 3-D a deformed point has few neighbours within the adjacency (2.5 spacings), and
// 3-D links cut the raised patch into hundreds of pieces, most below min_points (3.5 % of a
// 20 % patch found at 1 M points). LZD regions are linked in plan: one region holds the patch.
TEST(DeformationAnalysis, DenseNoisySurfaceGivesOneRegion)
{
  const synth::LiSurface li = denseGrid(8.0, synth::DeformationPosition::UPPER_RIGHT);
  const LiPair pair(li);
  const DeformationResult r = pair.run(DeformationSettings());
  ASSERT_TRUE(r.ok()) << r.matching.message;
  EXPECT_LT(pair.errorSigma(r.matching.adjustment.transformation), 0.5);
  std::size_t in_region = 0;
  for (std::size_t i = 0; i < li.deformed.size(); ++i)
    in_region += li.deformed[i] && r.regions.region[i] == 1;
  EXPECT_GT(static_cast<double>(in_region), 0.95 * static_cast<double>(li.deformed_indices.size()));
  EXPECT_EQ(r.regions.regions.size(), 1u);
  const Detection d = score(r, li);
  EXPECT_GE(d.precision, 0.99);
}

// Nearly flat terrain fixes heights and tilts but barely the position in plan: the rigid fit
// is refused ("the data do not determine the move"), and the analysis runs again with the
// translation alone, says so, and finds the raised middle. Without the fallback: no result.
TEST(DeformationAnalysis, FlatTerrainFallsBackToTheTranslation)
{
  const synth::LiSurface li = li_test::gentleTerrain();
  const LiPair pair(li);
  DeformationSettings s;
  s.translation_when_undetermined = false;
  const DeformationResult rigid = pair.run(s);
  ASSERT_FALSE(rigid.ok()) << "the case no longer needs the fallback";
  EXPECT_NE(rigid.matching.message.find("the data do not determine the move"), std::string::npos)
      << rigid.matching.message;
  const DeformationResult r = pair.run(DeformationSettings());
  ASSERT_TRUE(r.ok()) << r.matching.message;
  EXPECT_NE(r.model_note.find("translation only"), std::string::npos) << r.model_note;
  const Eigen::Matrix4d& T = r.matching.adjustment.transformation;
  EXPECT_TRUE((T.topLeftCorner<3, 3>().isIdentity(0.0))) << T;  // no rotation estimated
  EXPECT_LT(std::abs(T(2, 3)), 0.01);                           // the height is determined (noise 3 cm)
  const Detection d = score(r, li);
  EXPECT_GE(d.precision, 0.8);
  EXPECT_GE(d.recall, 0.95);
  EXPECT_NEAR(r.regions.percent_deformed, li.percent, 8.0);
  // The map a client reads says so too.
  const DeformationMap map = makeDeformationMap(pair.points, r, DeformationMapSettings());
  std::string subtitle;
  for (const std::string& line : map.style.subtitle)
    subtitle += line + " ";
  EXPECT_NE(subtitle.find("translation only"), std::string::npos) << subtitle;
}

// A dense grid far from its start: 200 × 200 nodes at 8-unit spacing (1600 units across, the
// relief of the 5000-unit surface) with Table 4's start, 500 units and 5° off. Seen from 500
// units above steep relief, LZD's first neighbourhood lies on the nearest slope and one
// re-centring does not reach the surface below: the least-squares start had "0 observations".
// Re-centred until the height settles, the matching converges and the patch is found.
TEST(DeformationAnalysis, DenseGridFarFromItsStartIsMatched)
{
  const synth::LiSurface li = denseGrid(8.0, synth::DeformationPosition::UPPER_LEFT);
  const LiPair pair(li);
  const DeformationResult r = pair.run(DeformationSettings());
  ASSERT_TRUE(r.ok()) << r.matching.message;
  EXPECT_EQ(r.matching.termination, TerminationType::CONVERGED) << r.matching.message;
  EXPECT_LT(pair.errorSigma(r.matching.adjustment.transformation), 0.5);
  EXPECT_NEAR(r.regions.percent_deformed, li.percent, 3.0);
  EXPECT_GT(r.field.observed, 38000u);  // of 40000
}

// LMS at 25 % deformed by only N(4σ, σ): without the cap, the M-step starts from a subset fit
// that compromises between the stable and the raised part, keeps its inflated scale (σ* ≈ 1.45 σ)
// and ends there, 2.5–3 σ off at the far corner, with no region found. The noise of neighbouring
// residuals (≈ σ) is what the M-step needs: capped by it, both cases recover the truth.
TEST(DeformationAnalysis, NeighbourNoiseCapBreaksTheCompromise)
{
  const std::pair<synth::DeformationPosition, std::uint32_t> cases[] = {
      {synth::DeformationPosition::LEFT, 2u}, {synth::DeformationPosition::LOWER, 2u}};
  for (const auto& c : cases) {
    const LiPair pair(liSurface(25.0, 4.0, c.first, c.second));
    DeformationSettings s;
    s.matching.method = RobustMethod::LMS;
    s.matching.block_start = false;  // the cap alone: no choice between starts (test_start_choice)
    s.matching.cap_scale_by_neighbour_noise = false;
    const DeformationResult uncapped = pair.run(s);
    ASSERT_TRUE(uncapped.ok()) << uncapped.matching.message;
    EXPECT_GT(pair.errorSigma(uncapped.matching.adjustment.transformation), 1.0)
        << "seed " << c.second << ": the case no longer shows the compromise";
    EXPECT_GT(uncapped.matching.high_breakdown_scale, 1.3 * kSigma);
    s.matching.cap_scale_by_neighbour_noise = true;
    const DeformationResult capped = pair.run(s);
    ASSERT_TRUE(capped.ok()) << capped.matching.message;
    EXPECT_LT(pair.errorSigma(capped.matching.adjustment.transformation), 0.5) << "seed " << c.second;
    // σ_d sees the noise and the patch's own spread (√2 σ on a quarter of the nodes).
    EXPECT_GT(capped.matching.neighbour_noise, 0.95 * kSigma);
    EXPECT_LT(capped.matching.neighbour_noise, 1.25 * kSigma);
    EXPECT_LE(capped.matching.high_breakdown_scale, capped.matching.neighbour_noise);
    EXPECT_GE(capped.refinement.rounds, 1);
    const Detection d = score(capped, pair.li);
    EXPECT_GT(d.precision, 0.95);
    EXPECT_GT(d.recall, 0.8);
  }
}

// MM at 42 % deformed by N(5σ, σ): the LTS start is 0.15 σ off, but Tukey's M-step over every
// point keeps the patch's low tail (within c ŝ ≈ 5 σ) weighted and walks 5 σ away from it.
// Holding out the points beyond 2.5 ŝ of the start while they stay there keeps it near.
TEST(DeformationAnalysis, MmStepHoldsOutTheStartsOutliers)
{
  const LiPair pair(liSurface(42.0, 5.0, synth::DeformationPosition::LOWER_RIGHT, 1));
  DeformationSettings s;
  s.refinement.max_rounds = 0;  // the estimator's own answer
  s.matching.mm_hold_out_beyond_start = false;
  const DeformationResult all = pair.run(s);
  ASSERT_TRUE(all.ok()) << all.matching.message;
  EXPECT_LT(pair.errorSigma(all.matching.high_breakdown_transformation), 0.5)
      << "the start is no longer good";
  EXPECT_GT(pair.errorSigma(all.matching.adjustment.transformation), 3.0)
      << "the M-step no longer walks away";
  s.matching.mm_hold_out_beyond_start = true;
  const DeformationResult held = pair.run(s);
  ASSERT_TRUE(held.ok()) << held.matching.message;
  EXPECT_LT(pair.errorSigma(held.matching.adjustment.transformation),
            0.6 * pair.errorSigma(all.matching.adjustment.transformation));
  // About the patch (42 % of 2500 nodes) is held out, not the surface.
  EXPECT_GT(held.matching.held_out, 900u);
  EXPECT_LT(held.matching.held_out, 1250u);
  EXPECT_NE(held.matching.estimator.find("holding out"), std::string::npos);
  // With the refinement the answer reaches the truth.
  const DeformationResult refined = pair.run(DeformationSettings());
  ASSERT_TRUE(refined.ok()) << refined.matching.message;
  EXPECT_LT(pair.errorSigma(refined.matching.adjustment.transformation), 0.5);
}

// LMS at 25 % deformed by N(4σ, σ), its own answer (no refinement): the subset fit compromises
// between the stable and the raised part and the M-step keeps it, 3.0 / 2.5 σ off at the far
// corner; main reported it CONVERGED. Its stable part scatters by 1.35 / 1.36 σ_d (right fits
// on Li's grid: at most 1.04): the stable-scatter gate, switched on, refuses it. At 7σ the same
// estimator lands on the truth and stays converged. docs/HONESTY_API.md has the grid.
TEST(DeformationAnalysis, TiltedCompromiseIsRefusedByTheStableScatter)
{
  DeformationSettings s;
  s.matching.method = RobustMethod::LMS;
  s.refinement.max_rounds = 0;  // the estimator's own answer, as in Li's tables
  s.translation_when_undetermined = false;
  s.max_stable_scatter_ratio = 1.10;  // off by default (dense surfaces, deformation_analysis.h)
  for (const auto position : {synth::DeformationPosition::LEFT, synth::DeformationPosition::RIGHT}) {
    const LiPair pair(liSurface(25.0, 4.0, position, 2));
    DeformationSettings off = s;
    off.max_stable_scatter_ratio = 0.0;
    const DeformationResult ungated = pair.run(off);
    ASSERT_TRUE(ungated.ok()) << ungated.matching.message;
    EXPECT_GT(pair.errorSigma(ungated.matching.adjustment.transformation), 2.0)
        << synth::toString(position) << ": the case no longer shows the compromise";
    const DeformationResult gated = pair.run(s);
    EXPECT_FALSE(gated.ok()) << synth::toString(position);
    EXPECT_EQ(gated.matching.termination, TerminationType::UNRELIABLE);
    EXPECT_NE(gated.matching.message.find("the stable part scatters"), std::string::npos)
        << gated.matching.message;
    EXPECT_GT(gated.stable_scatter, 1.1 * gated.field_noise);
    ASSERT_TRUE(gated.matching.adjustment.hasEstimate());  // refused, but readable
  }
  const LiPair strong(liSurface(25.0, 7.0, synth::DeformationPosition::UPPER_LEFT, 1));
  const DeformationResult right = strong.run(s);
  ASSERT_TRUE(right.ok()) << right.matching.message;
  EXPECT_LT(strong.errorSigma(right.matching.adjustment.transformation), 0.5);
  EXPECT_LT(right.stable_scatter, 1.1 * right.field_noise);
  EXPECT_GT(right.stable_scatter, 0.9 * right.field_noise);  // both are the noise there
}
