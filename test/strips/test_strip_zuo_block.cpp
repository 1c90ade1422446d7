// Zuo et al. (2012) §4 on small generated blocks with known truth (synth/zuo_block.h): three
// strips, strip 2 the reference, strips 1 and 3 displaced by Table 2's corrections (tz −3.3 m,
// ty +1.8 / +3.6 m, ω 0.067° / 0.078°, scale tens of ppm), 7 parameters per strip, LND. Every
// parameter comes back within 3 σ, the correction within a fraction of the noise over the whole
// strip, and σ0 equals what a point-to-fitted-surface distance must show: √(σ_noise² + σ_surface²).
#include "strip_test_blocks.h"

#include <pcl_ls3d/synth/zuo_block.h>

#include <gtest/gtest.h>

#include <cstdio>

using namespace pcl_ls3d;
using namespace strip_test;

namespace {

// Zuo's set-up: 7 parameters per strip, strip 2 (index 1) the reference, the given rule.
strips::StripAdjustmentReport
adjustZuoBlock(const Block& b, ConjugateRuleType rule)
{
  strips::StripAdjustmentSettings settings;
  settings.model = ParameterModel::SIMILARITY_7;
  settings.reference_strips = {1};
  settings.rule = rule;
  strips::StripBlockAdjustment adjustment;
  adjustment.setSettings(settings);
  strips::StripAdjustmentReport r;
  std::string error;
  EXPECT_TRUE(adjustment.run(b.strips, r, error)) << error;
  return r;
}

// `k_sigma`: bound on |estimate − truth| / σ per parameter, and on the mean correction error
// over the strip against the σ the covariance gives it (meanDisplacementSigma); `max_error`
// [m]: an absolute bound on that error (a fraction of the noise).
void
expectRecovered(synth::LandscapeType type, double scale, double k_sigma, double max_error)
{
  const synth::StripSettings s = synth::zuoBlock(type, scale, 2);
  const Block b = makeBlock(s);
  ASSERT_EQ(b.strips.size(), 3u);
  const strips::StripAdjustmentReport r = adjustZuoBlock(b, ConjugateRuleType::LND);
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_TRUE(r.strips[1].reference);
  for (std::size_t k : {0u, 2u}) {
    const Vector7d truth = trueParameters(b, k);
    ASSERT_GT(std::abs(truth[TZ]), 0.3) << "the errors are Zuo's, not small";
    for (int p = 0; p < 7; ++p)
      EXPECT_LE(std::abs(r.strips[k].parameters[p] - truth[p]), k_sigma * r.strips[k].sigmas[p])
          << synth::toString(type) << " strip " << k << " parameter " << p << ": "
          << r.strips[k].parameters[p] << " vs " << truth[p] << ", sigma " << r.strips[k].sigmas[p];
    const double error = meanDisplacementError(b, r, k), sigma = meanDisplacementSigma(b, r, k);
    EXPECT_GT(sigma, 0.0);
    EXPECT_LE(error, k_sigma * sigma) << synth::toString(type) << " strip " << k << ", sigma " << sigma;
    EXPECT_LE(error, max_error) << synth::toString(type) << " strip " << k << ", sigma " << sigma;
    std::printf("%s strip %zu: mean correction error %.4f m, its sigma %.4f m\n", synth::toString(type), k,
                error, sigma);
  }
  // σ0 is the σ of a point's distance to the other strip's local quadric: the point's noise and
  // the quadric's own height σ at the query (σ_surface, measured per observation by the rule).
  for (const auto& o : r.overlaps) {
    ASSERT_TRUE(o.used);
    const double expected = std::hypot(s.noise_sigma, o.sigma_surface);
    EXPECT_GT(o.sigma_surface, 0.1 * s.noise_sigma);
    EXPECT_NEAR(o.sigma0, expected, 0.1 * expected)
        << synth::toString(type) << " overlap " << o.i << "-" << o.j;
  }
}

}  // namespace

// Mountainous block at 0.2 of Zuo's size (400 m × 503 m strips, 70 m overlaps, 2.3 pts/m²):
// every parameter and the mean correction error within 3 σ, that error below the noise
// (measured with scan lines at random phases: 3.6 / 1.9 cm against σ 2.1 / 1.2 cm).
TEST(StripZuoBlock, MountainRecoversTable2Corrections)
{
  expectRecovered(synth::LandscapeType::MOUNTAIN, 0.2, 3.0, 0.05);
}

// Urban block at 0.25 of Zuo's size (500 m × 387 m strips, 66 m overlaps, 4.1 pts/m²): the
// same bounds (measured 2.0 / 0.9 cm against σ 1.2 / 1.3 cm). On the regular scan lattice
// before 2026-11-27 the heading κ and the scale of strip 1 ended 3.4–4.1 σ off here.
TEST(StripZuoBlock, UrbanRecoversTable2Corrections)
{
  expectRecovered(synth::LandscapeType::URBAN, 0.25, 3.0, 0.05);
}

// ICP's closest points on the urban block's flat ground stop metres from the truth (Zuo's 3 m
// errors, no coarse alignment). Such a result must not be delivered as a solution: UNRELIABLE,
// with the check that saw it named in the message.
namespace {

void
expectIcpNotConfirmed(std::uint32_t seed, const std::string& reason)
{
  const synth::StripSettings s = synth::zuoBlock(synth::LandscapeType::URBAN, 0.2, seed);
  const Block b = makeBlock(s);
  const strips::StripAdjustmentReport r = adjustZuoBlock(b, ConjugateRuleType::ICP);
  ASSERT_EQ(r.strips.size(), 3u);
  ASSERT_GT(std::max(meanDisplacementError(b, r, 0), meanDisplacementError(b, r, 2)), 0.3)
      << "the premise: ICP stops far from the truth here";
  EXPECT_EQ(r.termination, TerminationType::UNRELIABLE) << r.message;
  EXPECT_NE(r.message.find(reason), std::string::npos) << r.message;
}

}  // namespace

// Seed 1: the overlap psid1–psid2 keeps a median offset of 0.15 m along its normals (~0 after a
// right adjustment); before the offset check this was an iteration-limit result with exit 0 (at
// 0.4 of Zuo's size, CONVERGED 1.8 m off).
TEST(StripZuoBlock, IcpStoppedOffTheTruthIsNotConfirmed)
{
  expectIcpNotConfirmed(1, "still offset");
}

// Seed 2: ICP stops 1.6 m off with no median offset and the spread at the noise level, and was
// CONVERGED; LND's distances at that result still ask for a move of 0.17 m at 20 σ.
TEST(StripZuoBlock, IcpResultWhereLndIsNotAtRestIsNotConfirmed)
{
  expectIcpNotConfirmed(2, "still ask for a move");
}
