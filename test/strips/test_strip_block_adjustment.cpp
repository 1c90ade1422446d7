// Strip block adjustment (strips/strip_block_adjustment.h) on generated blocks with known
// per-strip errors: every strip's correction is recovered within its σ and a fraction of the
// noise; the datum options (first strip, another reference, soft weights) all work; a strip
// without overlap is reported and left unchanged; flat overlaps flag the horizontal
// parameters undeterminable instead of returning confident numbers.
#include "strip_test_blocks.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

using namespace pcl_ls3d;
using namespace strip_test;

namespace {

strips::StripAdjustmentReport
adjust(const Block& b, const strips::StripAdjustmentSettings& settings)
{
  strips::StripBlockAdjustment adjustment;
  adjustment.setSettings(settings);
  strips::StripAdjustmentReport report;
  std::string error;
  EXPECT_TRUE(adjustment.run(b.strips, report, error)) << error;
  return report;
}

}  // namespace

TEST(StripBlockAdjustment, ThreeStripsRecoverTheirCorrections)
{
  const Block b = makeBlock(smallBlock(3, 3));
  ASSERT_EQ(b.strips.size(), 3u);
  strips::StripAdjustmentSettings settings;
  settings.reference_strips = {0};
  const strips::StripAdjustmentReport r = adjust(b, settings);
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_LT(r.iterations, 20);
  EXPECT_TRUE(r.strips[0].reference);
  // σ0 is the σ of one point-to-surface distance: the point's noise plus the σ of the
  // conjugate surface at the query, a quadric fitted to LND's 20 (or 60) neighbours. That σ is
  // the quadric's height variance factor q_aa at the query times the fit's residual variance,
  // measured per observation (sigma_surface); 6/20 would be the mean leverage over the fitted
  // points, not the variance at the query. So σ0 ≈ √(σ_noise² + σ_surface²).
  for (const auto& o : r.overlaps) {
    const double expected_sigma0 = std::hypot(0.05, o.sigma_surface);
    EXPECT_NEAR(o.sigma0, expected_sigma0, 0.1 * expected_sigma0);
  }
  for (std::size_t k = 1; k < 3; ++k) {
    const Vector7d truth = trueParameters(b, k);
    for (int p = 0; p < 6; ++p) {
      ASSERT_TRUE(r.strips[k].determinable[static_cast<std::size_t>(p)]) << k << " " << p;
      EXPECT_LT(std::abs(r.strips[k].parameters[p] - truth[p]), 3.5 * r.strips[k].sigmas[p])
          << "strip " << k << " parameter " << p << " sigma " << r.strips[k].sigmas[p];
    }
    EXPECT_FALSE(r.strips[k].fixed[SCALE] == false) << "m is fixed in the rigid model";
    // Two 36 m wide overlaps of 2 pts/m², the outer strip beyond the reference's neighbour: the
    // error is within 3× the displacement σ the covariance gives (measured 2.1 / 3.9 cm against
    // σ 1.7 / 3.0 cm) and, as a gross check, within twice the noise.
    const double error = meanDisplacementError(b, r, k), sigma = meanDisplacementSigma(b, r, k);
    std::printf("strip %zu: mean correction error %.4f m, its sigma %.4f m\n", k, error, sigma);
    EXPECT_LT(error, 3.0 * sigma) << "strip " << k;
    EXPECT_LT(error, 2.0 * 0.05) << "strip " << k;
  }
  // Overlaps: both used, discrepancies shrink to about the noise.
  ASSERT_EQ(r.overlaps.size(), 2u);
  for (const auto& o : r.overlaps) {
    EXPECT_TRUE(o.used);
    EXPECT_LT(o.after.rms, 0.075);
    EXPECT_LT(o.after.sigma_mad, 0.065);
  }
}

namespace {

// Mean |A x − B x| over every 7th point of strip k.
double
meanDifference(const Block& b, std::size_t k, const Eigen::Matrix4d& A, const Eigen::Matrix4d& B)
{
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < b.strips[k].size(); i += 7, ++n)
    sum += ((A - B) * b.strips[k].blockPoint(i).homogeneous()).head<3>().norm();
  return sum / static_cast<double>(n);
}

}  // namespace

TEST(StripBlockAdjustment, DatumOptionsGiveTheSameRelativeCorrections)
{
  const Block b = makeBlock(smallBlock(3, 5));
  const auto truth = [&b](std::size_t k) -> Eigen::Matrix4d {
    return b.generated.strips[k].transform.matrix();
  };
  // Default datum: the strip with the largest overlap area, the middle one.
  strips::StripAdjustmentSettings settings;
  const strips::StripAdjustmentReport r1 = adjust(b, settings);
  ASSERT_TRUE(r1.converged()) << r1.message;
  EXPECT_FALSE(r1.strips[0].reference);
  EXPECT_TRUE(r1.strips[1].reference);
  EXPECT_FALSE(r1.strips[2].reference);
  EXPECT_TRUE(r1.strips[1].transformation.isIdentity(0.0));
  // The block lands in strip 2's frame: T_k ≈ T_2,true⁻¹ T_k,true.
  for (std::size_t k : {0u, 2u})
    EXPECT_LT(meanDifference(b, k, r1.strips[k].transformation, truth(1).inverse() * truth(k)), 0.04) << k;

  // Soft datum (Zuo eqs. 9-10 per strip): no strip fixed, relative corrections as above.
  settings.soft_datum = true;
  const strips::StripAdjustmentReport r2 = adjust(b, settings);
  ASSERT_TRUE(r2.converged()) << r2.message;
  for (const auto& s : r2.strips) {
    EXPECT_FALSE(s.reference);
    EXPECT_TRUE(s.determinable[0] && s.determinable[5]);
  }
  for (std::size_t k : {1u, 2u}) {
    const Eigen::Matrix4d relative = r2.strips[0].transformation.inverse() * r2.strips[k].transformation;
    EXPECT_LT(meanDifference(b, k, relative, truth(0).inverse() * truth(k)), 0.05) << k;
  }
  // An out-of-range reference is an error, not a silent default.
  settings.soft_datum = false;
  settings.reference_strips = {7};
  strips::StripBlockAdjustment adjustment;
  adjustment.setSettings(settings);
  strips::StripAdjustmentReport r3;
  std::string error;
  EXPECT_FALSE(adjustment.run(b.strips, r3, error));
  EXPECT_FALSE(error.empty());
}

TEST(StripBlockAdjustment, OneWayMatchingAndTheMinimumOfObservedPointsAreHonoured)
{
  const Block b = makeBlock(smallBlock(3, 3));
  strips::StripAdjustmentSettings settings;
  settings.reference_strips = {0};
  const strips::StripAdjustmentReport both = adjust(b, settings);
  settings.both_directions = false;
  const strips::StripAdjustmentReport one = adjust(b, settings);
  ASSERT_TRUE(both.converged()) << both.message;
  ASSERT_TRUE(one.converged()) << one.message;
  // One way: each overlap observes only its first strip's points, about half as many.
  ASSERT_EQ(one.overlaps.size(), both.overlaps.size());
  for (std::size_t o = 0; o < one.overlaps.size(); ++o) {
    EXPECT_GT(one.overlaps[o].observations, 0.3 * both.overlaps[o].observations) << o;
    EXPECT_LT(one.overlaps[o].observations, 0.7 * both.overlaps[o].observations) << o;
  }
  for (std::size_t k = 1; k < 3; ++k)
    EXPECT_LT(meanDisplacementError(b, one, k), 0.05) << k;

  // A direction with fewer observed points than the minimum is not matched: above every
  // overlap's count, nothing is observed and no strip is adjusted.
  settings.both_directions = true;
  settings.min_overlap_observations = 10 * both.overlaps[0].observations + 10 * both.overlaps[1].observations;
  strips::StripBlockAdjustment adjustment;
  adjustment.setSettings(settings);
  strips::StripAdjustmentReport none;
  std::string error;
  const bool ran = adjustment.run(b.strips, none, error);
  std::printf("min observations above every overlap: ran %d, %s / %s\n", ran, error.c_str(),
              none.message.c_str());
  EXPECT_FALSE(ran && none.converged());
}

TEST(StripBlockAdjustment, StripWithoutOverlapIsReportedAndLeftUnchanged)
{
  Block b = makeBlock(smallBlock(3, 3));
  // A fourth strip 5 km away: a copy of strip 3 shifted in x.
  strips::Strip far = b.strips[2];
  far.name = "far";
  far.point_source_id = 99;
  far.origin.x() += 5000.0;
  b.strips.push_back(far);
  strips::StripAdjustmentSettings settings;
  settings.reference_strips = {0};
  const strips::StripAdjustmentReport r = adjust(b, settings);
  ASSERT_TRUE(r.converged()) << r.message;
  ASSERT_EQ(r.strips.size(), 4u);
  EXPECT_FALSE(r.strips[3].adjusted);
  EXPECT_TRUE(r.strips[3].transformation.isIdentity(0.0));
  EXPECT_FALSE(r.strips[3].note.empty());
  for (std::size_t k = 1; k < 3; ++k) {
    EXPECT_TRUE(r.strips[k].adjusted);
    EXPECT_LT(meanDisplacementError(b, r, k), 0.04) << k;
  }
}
TEST(StripBlockAdjustment, FlatOverlapsFlagHorizontalParametersUndeterminable)
{
  synth::StripSettings s = smallBlock(3, 3);
  s.relief = 0.0;
  s.buildings = false;
  const Block b = makeBlock(s);
  strips::StripAdjustmentSettings settings;
  settings.reference_strips = {0};
  const strips::StripAdjustmentReport r = adjust(b, settings);
  ASSERT_NE(r.termination, TerminationType::NOT_RUN);
  for (std::size_t k = 1; k < 3; ++k) {
    const auto& d = r.strips[k].determinable;
    // A plane fixes height and the two tilts, never the horizontal shift or the heading.
    EXPECT_FALSE(d[TX]) << k << " p " << r.strips[k].parameters.transpose() << " s "
                        << r.strips[k].sigmas.transpose();
    EXPECT_FALSE(d[TY]) << k;
    EXPECT_FALSE(d[KAPPA]) << k;
    EXPECT_TRUE(d[TZ]) << k;
    EXPECT_FALSE(std::isfinite(r.strips[k].sigmas[TX])) << "no confident number for tx";
    // What is determinable is right: the height at the strip centre.
    const Vector7d truth = trueParameters(b, k);
    EXPECT_LT(std::abs(r.strips[k].parameters[TZ] - truth[TZ]), 3.5 * r.strips[k].sigmas[TZ] + 0.01) << k;
  }
}

// The translation the discrepancies ask for: values v = −nᵀt + noise on tilted normals give t
// back within a few of its σ; values beyond max_abs (edges seen from two sides) do not count;
// normals in one plane cannot determine t (count 0).
TEST(StripDiscrepancies, AskedTranslationRecoversAKnownMove)
{
  const Eigen::Vector3d t(0.04, -0.07, 0.01);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.02), tilt(0.0, 0.3);
  strips::DiscrepancySamples s;
  for (int k = 0; k < 20000; ++k) {
    const Eigen::Vector3d n = Eigen::Vector3d(tilt(rng), tilt(rng), 1.0).normalized();
    s.xy.emplace_back(0.0, 0.0);
    s.normal.push_back(n.cast<float>());
    s.value.push_back(static_cast<float>(-n.dot(t) + noise(rng)));
  }
  for (int k = 0; k < 500; ++k) {  // a wall's worth of large values on one side
    s.xy.emplace_back(0.0, 0.0);
    s.normal.push_back(Eigen::Vector3f::UnitX());
    s.value.push_back(2.0f);
  }
  const strips::AskedTranslation a = strips::askedTranslation(s, 0.5);
  ASSERT_EQ(a.count, 20000u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(a.sigma[c], 0.0);
    EXPECT_NEAR(a.t[c], t[c], 4.0 * a.sigma[c]) << "axis " << c;
  }
  EXPECT_LT(strips::askedTranslation(s, 5.0).t.x(), t.x() - 0.1) << "the wall counts without the cut";

  strips::DiscrepancySamples flat;
  for (int k = 0; k < 100; ++k) {
    flat.xy.emplace_back(0.0, 0.0);
    flat.normal.push_back(Eigen::Vector3f::UnitZ());
    flat.value.push_back(0.01f);
  }
  EXPECT_EQ(strips::askedTranslation(flat, 1.0).count, 0u);
}
