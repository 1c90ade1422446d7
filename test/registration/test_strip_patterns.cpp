// LND / LZD register two generated flight strips with both scan patterns. Zig-zag scan lines
// converge towards the swath edge, where most 12-nearest-neighbour sets of the target lie on two
// scan lines: a local quadric fitted to them is undetermined across the lines, and before the
// conditioning check in the rules this converged 0.4–0.5 m off (parallel lines: ~1 cm).
#include "ls3d_test_utils.h"

#include <pcl_ls3d/synth/strip_block.h>

#include <gtest/gtest.h>

#include <cstdio>

using namespace ls3d_test;

namespace {

using Param = std::tuple<pcl_ls3d::ConjugateRuleType, pcl_ls3d::synth::ScanPattern>;

class StripPatterns : public ::testing::TestWithParam<Param>
{};

}  // namespace

TEST_P(StripPatterns, RecoversStripDisplacement)
{
  namespace synth = pcl_ls3d::synth;
  synth::StripSettings s;
  s.seed = 3;
  s.num_strips = 2;
  s.pattern = std::get<1>(GetParam());
  s.swath_width = 150.0;               // 300 points per scan line at 4 pts/m²
  s.side_overlap = 0.4;                // 60 m shared band
  s.strip_length = 150.0;              // 90 000 points per strip
  const double noise = s.noise_sigma;  // 5 cm per axis
  const synth::StripBlock block = synth::makeStripBlock(s);
  ASSERT_EQ(block.strips.size(), 2u);
  const Cloud::ConstPtr target = block.stripCloud(0);
  const Cloud::ConstPtr source = block.stripCloud(1);
  const Eigen::Matrix4d truth =
      block.strips[0].transform.inverse().matrix() * block.strips[1].transform.matrix();

  LS3D ls3d;
  ls3d.setConjugateRule(std::get<0>(GetParam()));
  ls3d.setMaxCorrespondenceDistance(2.0);
  ls3d.setInputSource(source);
  ls3d.setInputTarget(target);
  Cloud aligned;
  ls3d.align(aligned);
  ASSERT_TRUE(ls3d.hasConverged()) << ls3d.getReport().fullReport();
  const auto err = displacementError(*source, ls3d.getFinalTransformation().cast<double>(), truth);
  std::printf("%s %s: sigma0 %.4f observations %zu displacement mean %.4f max %.4f\n",
              ls3d.getReport().rule_name.c_str(),
              s.pattern == synth::ScanPattern::ZIGZAG ? "zigzag" : "parallel", ls3d.getReport().sigma0,
              ls3d.getReport().observations_used, err.mean, err.max);
  // ~3.5·10^4 observations in the band; the error is extrapolated over the whole 150 m swath.
  // Both patterns: below half a noise σ on average and one σ at worst (measured 9–11 / 17–21 mm;
  // before the conditioning check zig-zag gave 0.4–0.5 m on benchmark_scaling's strips, and with
  // the check but 12 neighbours 64 / 130 mm here). σ0 must be that of two noisy surfaces, not
  // inflated by tilted patches (before: 0.073 m on zig-zag).
  EXPECT_LT(err.mean, 0.5 * noise);
  EXPECT_LT(err.max, 1.0 * noise);
  EXPECT_LT(ls3d.getReport().sigma0, 1.2 * noise);
}

INSTANTIATE_TEST_SUITE_P(Ls3d, StripPatterns,
                         ::testing::Combine(::testing::Values(pcl_ls3d::ConjugateRuleType::LND,
                                                              pcl_ls3d::ConjugateRuleType::LZD),
                                            ::testing::Values(pcl_ls3d::synth::ScanPattern::ZIGZAG,
                                                              pcl_ls3d::synth::ScanPattern::PARALLEL)));
