// Each conjugate-point rule recovers the known 7-parameter truth of generated terrain pairs:
// equal densities, 1 vs 4 pts/m², 30 % and 70 % overlap, σ = 5 cm noise (rules × cases).
#include "ls3d_test_utils.h"

#include <gtest/gtest.h>

#include <cstdio>

using namespace ls3d_test;

namespace {

struct Case
{
  const char* name;
  double src_density, tgt_density, overlap, noise;
};

const Case kCases[] = {
    {"EqualDensity", 1.0, 1.0, 0.7, 0.02},
    {"Sparse1VsDense4", 1.0, 4.0, 0.7, 0.02},
    {"Overlap30", 1.0, 1.0, 0.3, 0.02},
    {"Overlap70", 1.0, 1.0, 0.7, 0.02},
    {"Noise5cm", 1.0, 1.0, 0.7, 0.05},
};

using Param = std::tuple<pcl_ls3d::ConjugateRuleType, int>;

class RuleAccuracy : public ::testing::TestWithParam<Param>
{};

std::string
paramName(const ::testing::TestParamInfo<Param>& info)
{
  const char* rules[] = {"LND", "LZD", "ICP"};
  return std::string(rules[static_cast<int>(std::get<0>(info.param))]) + "_" +
         kCases[std::get<1>(info.param)].name;
}

}  // namespace

TEST_P(RuleAccuracy, RecoversKnownSimilarity)
{
  const auto rule = std::get<0>(GetParam());
  const Case& c = kCases[std::get<1>(GetParam())];
  const auto pair = smallPair(7, 120.0, c.src_density, c.tgt_density, c.overlap, c.noise, 60.0);
  ASSERT_GT(pair.source->size(), 1000u);

  LS3D ls3d;
  ls3d.setConjugateRule(rule);
  ls3d.setInputSource(pair.source);
  ls3d.setInputTarget(pair.target);
  Cloud aligned;
  ls3d.align(aligned);
  ASSERT_TRUE(ls3d.hasConverged()) << ls3d.getReport().fullReport();
  const auto& r = ls3d.getReport();
  const auto err =
      displacementError(*pair.source, ls3d.getFinalTransformation().cast<double>(), pair.truth.matrix());
  const pcl_ls3d::Vector7d truth = truthInReducedFrame(r, pair.truth);
  std::printf("%s %s: iters %d sigma0 %.4f obs %zu  disp mean %.4f max %.4f | dX/sigma:",
              r.rule_name.c_str(), c.name, r.iterations, r.sigma0, r.observations_used, err.mean,
              err.max);
  for (int i = 0; i < 7; ++i)
    std::printf(" %.2f", (r.parameters[i] - truth[i]) / r.sigmas[i]);
  std::printf("\n   err:");
  for (int i = 0; i < 7; ++i)
    std::printf(" %.2e", r.parameters[i] - truth[i]);
  std::printf("\n   sig:");
  for (int i = 0; i < 7; ++i)
    std::printf(" %.2e", r.sigmas[i]);
  std::printf("\n");
  if (c.noise > 0.04) std::printf("%s\n", r.fullReport().c_str());
}

INSTANTIATE_TEST_SUITE_P(
    Ls3d, RuleAccuracy,
    ::testing::Combine(::testing::Values(pcl_ls3d::ConjugateRuleType::LND,
                                         pcl_ls3d::ConjugateRuleType::LZD,
                                         pcl_ls3d::ConjugateRuleType::ICP),
                       ::testing::Range(0, 5)),
    paramName);
