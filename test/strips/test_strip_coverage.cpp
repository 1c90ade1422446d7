// Monte-Carlo coverage of the strip adjustment's σ (issue 8): over 24 generated 3-strip blocks
// (fresh terrain, errors and noise per seed), the share of |estimate − truth| ≤ σ and ≤ 2σ
// pooled over the 12 free parameters must be near 68 % / 95 %. Bounds are 3 binomial σ wide
// around the nominal values on 288 samples (but per-block correlations widen the spread), so
// σ 1.5× too small (45 % / 82 %) or too large (87 % / 99.6 %) fails.
#include "strip_test_blocks.h"

#include <gtest/gtest.h>

using namespace pcl_ls3d;
using namespace strip_test;

TEST(StripCoverage, SigmaCoversTheTruth)
{
  int n = 0, within1 = 0, within2 = 0;
  for (std::uint32_t seed = 1; seed <= 24; ++seed) {
    synth::StripSettings s = smallBlock(3, seed);
    s.strip_length = 160.0;
    s.swath_width = 90.0;
    const Block b = makeBlock(s);
    strips::StripAdjustmentSettings settings;
    settings.reference_strips = {0};
    strips::StripBlockAdjustment adjustment;
    adjustment.setSettings(settings);
    strips::StripAdjustmentReport r;
    std::string error;
    ASSERT_TRUE(adjustment.run(b.strips, r, error)) << error;
    ASSERT_TRUE(r.converged()) << "seed " << seed << ": " << r.message;
    for (std::size_t k = 1; k < 3; ++k) {
      const Vector7d truth = trueParameters(b, k);
      for (int p = 0; p < 6; ++p, ++n) {
        const double e = std::abs(r.strips[k].parameters[p] - truth[p]), sigma = r.strips[k].sigmas[p];
        within1 += e <= sigma;
        within2 += e <= 2.0 * sigma;
      }
    }
  }
  const double c1 = static_cast<double>(within1) / n, c2 = static_cast<double>(within2) / n;
  std::printf("coverage over %d parameters: %.1f %% within sigma, %.1f %% within 2 sigma\n", n, 100.0 * c1,
              100.0 * c2);
  EXPECT_GT(c1, 0.58);
  EXPECT_LT(c1, 0.80);
  EXPECT_GT(c2, 0.89);
  EXPECT_LE(c2, 0.995);
}
