// The strip adjustment says when its model is too small (model_adequacy.h, issue 45): on
// generated blocks with known truth, a rigid truth stays CONVERGED with held-out scales that
// are not significant, a block whose strips carry scales that move their ends by more than the
// noise ends NOT CONFIRMED naming the strips and -params 7, and -params 7 on that block
// converges within its σ. The freed scales the test reports agree with the truth.
#include "strip_test_blocks.h"

#include <gtest/gtest.h>

#include <cstdio>

using namespace pcl_ls3d;
using namespace strip_test;

namespace {

// Three 600 m × 120 m strips at 1.5 pts/m², noise 3 cm, 30 % side overlap; strip 1 the
// reference (identity). Scales of +250 and −200 ppm move the ends of strips 2 and 3 (radius
// ≈ 306 m) by 7.6 and 6.1 cm, twice the noise.
synth::StripSettings
longStrips(double scale2, double scale3, std::uint32_t seed = 5)
{
  synth::StripSettings s = smallBlock(3, seed);
  s.strip_length = 600.0;
  s.density = 1.5;
  s.noise_sigma = 0.03;
  s.errors = {identityParameters(),
              (Vector7d() << 0.2, -0.15, 0.1, 2e-4, -3e-4, 4e-4, 1.0 + scale2).finished(),
              (Vector7d() << -0.1, 0.25, -0.2, -3e-4, 2e-4, -2e-4, 1.0 + scale3).finished()};
  return s;
}

strips::StripAdjustmentReport
adjust(const Block& b, ParameterModel model)
{
  strips::StripAdjustmentSettings settings;
  settings.reference_strips = {0};
  settings.model = model;
  strips::StripBlockAdjustment adjustment;
  adjustment.setSettings(settings);
  strips::StripAdjustmentReport report;
  std::string error;
  EXPECT_TRUE(adjustment.run(b.strips, report, error)) << error;
  return report;
}

// The true scale of strip k relative to the reference (strip 0, identity).
double
trueScale(const Block& b, std::size_t k)
{
  return b.generated.strips[k].transform.m - 1.0;
}

void
print(const strips::StripAdjustmentReport& r, const Block& b)
{
  for (std::size_t k = 1; k < r.strips.size(); ++k)
    for (const auto& h : r.strips[k].held_out)
      std::printf(
          "strip %zu: held-out m-1 %+.1f ppm +- %.1f (formal %.1f), z %+.2f, effect %.4f, noise %.4f, "
          "truth %+.1f ppm\n",
          k, 1e6 * h.estimate, 1e6 * h.sigma, 1e6 * h.sigma_formal, h.z, h.effect, h.noise,
          1e6 * trueScale(b, k));
}

}  // namespace

TEST(StripHeldOut, RigidTruthConvergesAndItsScalesAreNotSignificant)
{
  const Block b = makeBlock(longStrips(0.0, 0.0));
  const strips::StripAdjustmentReport r = adjust(b, ParameterModel::RIGID_6);
  print(r, b);
  ASSERT_EQ(r.termination, TerminationType::CONVERGED) << r.message;
  ASSERT_TRUE(r.held_out.tested) << r.held_out.note;
  EXPECT_EQ(r.held_out.dof, 2);
  EXPECT_EQ(r.held_out.flagged, 0);
  EXPECT_TRUE(r.strips[0].held_out.empty());  // the reference holds nothing out
  for (std::size_t k = 1; k < 3; ++k) {
    ASSERT_EQ(r.strips[k].held_out.size(), 1u);
    const strips::HeldOutParameter& h = r.strips[k].held_out[0];
    EXPECT_EQ(h.parameter, SCALE);
    EXPECT_GT(h.sigma, 0.0);
    EXPECT_GE(h.sigma, h.sigma_formal);
    EXPECT_LT(std::abs(h.z), 3.0) << "strip " << k;
    EXPECT_FALSE(h.flagged);
    EXPECT_GT(h.noise, 0.02);  // the strips' own noise, 3 cm
    EXPECT_LT(h.noise, 0.05);
  }
}

TEST(StripHeldOut, ScaledStripsAreNotConfirmedWithTheStripsAndTheOption)
{
  const Block b = makeBlock(longStrips(250e-6, -200e-6));
  const strips::StripAdjustmentReport r = adjust(b, ParameterModel::RIGID_6);
  print(r, b);
  ASSERT_TRUE(r.held_out.tested) << r.held_out.note;
  EXPECT_EQ(r.termination, TerminationType::UNRELIABLE) << r.message;
  EXPECT_NE(r.message.find("NOT CONFIRMED"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("-params 7"), std::string::npos) << r.message;
  for (std::size_t k = 1; k < 3; ++k) {
    ASSERT_EQ(r.strips[k].held_out.size(), 1u);
    const strips::HeldOutParameter& h = r.strips[k].held_out[0];
    EXPECT_TRUE(h.flagged) << "strip " << k;
    EXPECT_NE(r.message.find(r.strips[k].name), std::string::npos) << r.message;
    // The scale the test would free agrees with the truth within 3 of its σ.
    EXPECT_LT(std::abs(h.estimate - trueScale(b, k)), 3.0 * h.sigma) << "strip " << k;
  }
}

TEST(StripHeldOut, FreedScaleConvergesWithinItsSigma)
{
  const Block b = makeBlock(longStrips(250e-6, -200e-6));
  const strips::StripAdjustmentReport r = adjust(b, ParameterModel::SIMILARITY_7);
  ASSERT_EQ(r.termination, TerminationType::CONVERGED) << r.message;
  EXPECT_FALSE(r.held_out.tested);  // nothing held out
  for (std::size_t k = 1; k < 3; ++k) {
    const double error = meanDisplacementError(b, r, k), sigma = meanDisplacementSigma(b, r, k);
    std::printf("strip %zu: -params 7 error %.4f m, sigma %.4f m; m-1 %+.1f ppm +- %.1f, truth %+.1f\n", k,
                error, sigma, 1e6 * (r.strips[k].parameters[SCALE] - 1.0), 1e6 * r.strips[k].sigmas[SCALE],
                1e6 * trueScale(b, k));
    EXPECT_LT(error, 3.0 * sigma) << "strip " << k;
    EXPECT_LT(std::abs(r.strips[k].parameters[SCALE] - 1.0 - trueScale(b, k)),
              3.0 * r.strips[k].sigmas[SCALE]);
  }
}

TEST(StripHeldOut, TheTestCanBeSwitchedOffAndNeedsValidThresholds)
{
  strips::StripAdjustmentSettings s;
  std::string why;
  EXPECT_TRUE(s.isValid(&why)) << why;
  s.adjustment.held_out_z = 0.0;
  EXPECT_FALSE(s.isValid(&why));
  s.adjustment.held_out_z = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(s.isValid(&why)) << why;
  s.adjustment.held_out_noise_factor = -1.0;
  EXPECT_FALSE(s.isValid(&why));

  const Block b = makeBlock(longStrips(250e-6, -200e-6));
  strips::StripAdjustmentSettings off;
  off.reference_strips = {0};
  off.adjustment.held_out_z = std::numeric_limits<double>::infinity();
  strips::StripBlockAdjustment adjustment;
  adjustment.setSettings(off);
  strips::StripAdjustmentReport r;
  ASSERT_TRUE(adjustment.run(b.strips, r, why)) << why;
  EXPECT_FALSE(r.held_out.tested);
  EXPECT_EQ(r.termination, TerminationType::CONVERGED) << r.message;  // today's verdict without the test
}
