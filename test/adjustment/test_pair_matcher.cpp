// Stage 2 (pair_matcher.h): the design rows the matcher gives for BOTH parameter blocks are the
// derivatives of the observed distance l with respect to each block's parameters, checked by
// central differences with both bodies moving; observations are ordered and identified by
// source point. The matcher is frozen after the nominal match, so every perturbed match measures
// to the same local surface elements: l is then a smooth function of the parameters and the
// difference quotients are exact to O(h²) (without freezing, re-fitted elements would add the
// fitting noise of a new neighbourhood to each quotient).
#include <pcl_ls3d/adjustment/pair_matcher.h>

#include "engine_test_surfaces.h"

#include <gtest/gtest.h>

#include <map>

using namespace pcl_ls3d;
using engine_test::KdSurface;

namespace {

struct Fixture
{
  Eigen::Vector3d origin{30.0, 30.0, 0.0};
  KdSurface target{engine_test::sampleTerrain(0, 60, 0, 60, 0.5, 0.0, 1)};
  std::vector<Eigen::Vector3d> source =
      engine_test::reduce(engine_test::sampleTerrain(15, 45, 15, 45, 2.0, 0.0, 2), origin);

  ParameterBlock
  block(const Vector7d& values) const
  {
    ParameterBlock b;
    b.input_origin = b.output_origin = origin;
    b.values = values;
    return b;  // every parameter free
  }
};

const Vector7d kSourceValues = (Vector7d() << 0.05, -0.03, 0.02, 5e-4, -4e-4, 3e-4, 1.0001).finished();
const Vector7d kTargetValues = (Vector7d() << -0.02, 0.04, -0.01, -3e-4, 2e-4, 6e-4, 0.9999).finished();

// l of every observed point (component 0) under the given poses, with the frozen elements.
std::map<int, double>
distances(PairMatcher& matcher, const ParameterBlock& source, const ParameterBlock& target)
{
  std::map<int, double> l;
  for (const Observation& o : matcher.match(BlockLinearization(source), BlockLinearization(target), {}))
    l[o.point] = o.distance;
  return l;
}

class PairMatcherRows : public ::testing::TestWithParam<ConjugateRuleType>
{};

TEST_P(PairMatcherRows, BothBlocksRowsEqualTheNumericalDerivative)
{
  const Fixture f;
  const ConjugateRule::Ptr rule = makeConjugateRule(GetParam());
  PairMatcher matcher;
  matcher.reset(f.source, f.target.surface(), *rule, 2.0);
  const ParameterBlock source = f.block(kSourceValues), target = f.block(kTargetValues);
  const ObservationSet nominal = matcher.match(BlockLinearization(source), BlockLinearization(target), {});
  ASSERT_GT(nominal.size(), 150u);
  std::map<int, RowVector7d> source_rows, target_rows;
  for (const Observation& o : nominal) {
    // Within a small radius of a target sample the rules draw the surface towards it
    // (towardsNearestSample, tin_rules.cpp): a bump the rows deliberately leave out.
    pcl::Indices nearest(1);
    std::vector<float> sq(1);
    f.target.tree().nearestKSearch(pcl::PointXYZ(static_cast<float>(o.foot.x()),
                                                 static_cast<float>(o.foot.y()),
                                                 static_cast<float>(o.foot.z())),
                                   1, nearest, sq);
    if (sq[0] < 0.15f * 0.15f)
      continue;
    source_rows[o.point] = matcher.sourceRow(o);
    target_rows[o.point] = matcher.targetRow(o);
  }
  matcher.freeze();

  for (int side = 0; side < 2; ++side)
    for (int k = 0; k < 7; ++k) {
      const double h = k < 3 ? 1e-3 : 1e-5;
      ParameterBlock plus_s = source, minus_s = source, plus_t = target, minus_t = target;
      (side == 0 ? plus_s : plus_t).values[k] += h;
      (side == 0 ? minus_s : minus_t).values[k] -= h;
      const std::map<int, double> lp = distances(matcher, plus_s, plus_t);
      const std::map<int, double> lm = distances(matcher, minus_s, minus_t);
      const auto& rows = side == 0 ? source_rows : target_rows;
      std::size_t compared = 0;
      for (const auto& kv : rows) {
        const auto p = lp.find(kv.first), m = lm.find(kv.first);
        if (p == lp.end() || m == lm.end())
          continue;
        const double numeric = (p->second - m->second) / (2.0 * h);
        EXPECT_NEAR(kv.second[k], numeric, 1e-6 * (1.0 + std::abs(numeric)))
            << (side == 0 ? "source" : "target") << " parameter " << k << " point " << kv.first;
        ++compared;
      }
      EXPECT_EQ(compared, rows.size());
    }
}

INSTANTIATE_TEST_SUITE_P(Rules, PairMatcherRows,
                         ::testing::Values(ConjugateRuleType::LND, ConjugateRuleType::LZD,
                                           ConjugateRuleType::ICP));

TEST(PairMatcher, ObservationsAreOrderedBySourcePointAndCarryTheirGeometry)
{
  const Fixture f;
  const ConjugateRule::Ptr rule = makeConjugateRule(ConjugateRuleType::ICP);  // 3 per point
  PairMatcher matcher;
  matcher.reset(f.source, f.target.surface(), *rule, 2.0);
  const ParameterBlock source = f.block(kSourceValues);
  const ParameterBlock target = ParameterBlock::fixedIdentity(f.origin);
  const ObservationSet& set = matcher.match(BlockLinearization(source), BlockLinearization(target), {});
  ASSERT_GT(set.size(), 3u * 150u);
  for (std::size_t j = 1; j < set.size(); ++j) {
    const Observation &a = set[j - 1], &b = set[j];
    ASSERT_TRUE(a.point < b.point || (a.point == b.point && a.component + 1 == b.component));
  }
  for (const Observation& o : set) {
    // l = uᵀ(T_s(p) − q) with the target at the identity; q is a target point for ICP.
    EXPECT_NEAR(o.distance, o.direction.dot(matcher.position(o) - o.foot), 1e-9);
    EXPECT_TRUE(std::isfinite(o.surface_variance));
  }
  // Every other point only: the same points keep their indices.
  const ObservationSet& half =
      matcher.match(BlockLinearization(source), BlockLinearization(target), {2, false});
  for (const Observation& o : half)
    EXPECT_EQ(o.point % 2, 0);
}

}  // namespace
