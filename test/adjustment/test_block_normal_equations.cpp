// Stage 3 for many bodies (block_normal_equations.h): a toy block adjustment of three strips with
// the first one fixed recovers the known corrections of the other two through the engine's
// stages (pair matcher with both strips moving, overlap contributions, one block solve); the
// sparse and the dense solve agree; undeterminable parameters are flagged by both.
#include <pcl_ls3d/adjustment/block_normal_equations.h>
#include <pcl_ls3d/adjustment/pair_matcher.h>

#include "engine_test_surfaces.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

using namespace pcl_ls3d;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Strip k covers x in [30k − 5, 30k + 35]: neighbours overlap by 10 m.
struct Strip
{
  std::vector<Eigen::Vector3d> observed;  // coordinates as delivered (with the strip's error)
  Eigen::Matrix4d correction;             // true map observed → true frame
  Eigen::Vector3d origin;
  std::vector<Eigen::Vector3d> reduced;
  std::unique_ptr<engine_test::KdSurface> surface;
};

Strip
makeStrip(int k, const Vector7d& truth_local, unsigned seed)
{
  Strip s;
  const std::vector<Eigen::Vector3d> truth =
      engine_test::sampleTerrain(30.0 * k - 5.0, 30.0 * k + 35.0, 0.0, 60.0, 0.7, 0.002, seed);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& p : truth)
    centre += p;
  s.origin = centre / static_cast<double>(truth.size());
  s.correction = localToGlobal(SimilarityTransform(truth_local).matrix(), s.origin, s.origin);
  const Eigen::Matrix4d error = s.correction.inverse();
  for (const auto& p : truth)
    s.observed.push_back((error * p.homogeneous()).head<3>());
  s.reduced = engine_test::reduce(s.observed, s.origin);
  s.surface = std::make_unique<engine_test::KdSurface>(s.observed);
  return s;
}

// One iteration: the contributions of every overlap in both directions, summed.
BlockNormalEquations
assemble(const std::vector<Strip>& strips, const std::vector<ParameterBlock>& blocks,
         const ConjugateRule& rule)
{
  BlockNormalEquations ne(static_cast<int>(strips.size()));
  const std::pair<int, int> overlaps[] = {{0, 1}, {1, 0}, {1, 2}, {2, 1}};
  for (const auto& [i, j] : overlaps) {
    PairMatcher matcher;
    matcher.reset(strips[static_cast<std::size_t>(i)].reduced,
                  strips[static_cast<std::size_t>(j)].surface->surface(), rule, 1.0);
    const ObservationSet& set = matcher.match(BlockLinearization(blocks[static_cast<std::size_t>(i)]),
                                              BlockLinearization(blocks[static_cast<std::size_t>(j)]), {});
    PairNormalEquations pair;
    for (const Observation& o : set) {
      PairNormalEquations::Row row;
      row << matcher.sourceRow(o), matcher.targetRow(o);
      pair.add(row, o.distance, 1.0);
    }
    pair.symmetrize();
    ne.addOverlap(i, j, pair);
  }
  return ne;
}

GaussMarkovProblem
problemOf(const std::vector<ParameterBlock>& blocks)
{
  GaussMarkovProblem p(7 * static_cast<int>(blocks.size()));
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    p.current.segment<7>(7 * static_cast<Eigen::Index>(b)) = blocks[b].values;
    p.apriori_values.segment<7>(7 * static_cast<Eigen::Index>(b)) = blocks[b].apriori_values;
    p.apriori_weights.segment<7>(7 * static_cast<Eigen::Index>(b)) = blocks[b].apriori_weights;
    p.scaling.segment<4>(7 * static_cast<Eigen::Index>(b) + 3).setConstant(1.0 / 30.0);
  }
  return p;
}

TEST(BlockAdjustment, ThreeStripsWithTheFirstFixedRecoverTheirCorrections)
{
  std::vector<Strip> strips;
  strips.push_back(makeStrip(0, (Vector7d() << 0, 0, 0, 0, 0, 0, 1).finished(), 11));
  strips.push_back(makeStrip(1, (Vector7d() << 0.30, -0.20, 0.15, 1e-3, -8e-4, 1.2e-3, 1).finished(), 12));
  strips.push_back(makeStrip(2, (Vector7d() << -0.25, 0.35, -0.10, -6e-4, 9e-4, -1e-3, 1).finished(), 13));
  std::vector<ParameterBlock> blocks(3);
  for (std::size_t k = 0; k < 3; ++k) {
    blocks[k].input_origin = blocks[k].output_origin = strips[k].origin;
    blocks[k].apriori_weights = parameterModelWeights(ParameterModel::RIGID_6);
  }
  blocks[0].apriori_weights.setConstant(kInf);  // the datum
  const ConjugateRule::Ptr rule = makeConjugateRule(ConjugateRuleType::LND);
  for (int it = 0; it < 12; ++it) {
    const BlockNormalEquations ne = assemble(strips, blocks, *rule);
    const GaussMarkovSolution dense = solveGaussMarkov(ne, problemOf(blocks));
    const GaussMarkovSolution sparse = solveGaussMarkov(ne, problemOf(blocks), 0);
    ASSERT_TRUE(dense.ok && sparse.ok) << dense.message << " / " << sparse.message;
    EXPECT_EQ(dense.unknowns, 12);
    EXPECT_LT((dense.dx - sparse.dx).norm(), 1e-9 * (1.0 + dense.dx.norm()));
    EXPECT_LT((dense.qxx - sparse.qxx).norm(), 1e-9 * dense.qxx.norm());
    for (std::size_t k = 0; k < 3; ++k)
      blocks[k].values += dense.dx.segment<7>(7 * static_cast<Eigen::Index>(k));
    if (dense.dx.cwiseAbs().maxCoeff() < 1e-9)
      break;
  }
  EXPECT_EQ(blocks[0].values, identityParameters());
  for (std::size_t k = 1; k < 3; ++k) {
    double worst = 0.0;  // displacement of the recovered minus the true correction
    for (const auto& p : strips[k].observed)
      worst = std::max(worst, ((blocks[k].matrix() - strips[k].correction) * p.homogeneous()).norm());
    // Noise 2 mm per coordinate: measured 1.5 / 2.7 mm (0.4 / 0.5 mm without noise, 1.0 / 1.8 cm
    // with 1 cm: the error is the precision of two 10 m wide overlaps, not a bias).
    EXPECT_LT(worst, 0.006) << "strip " << k;
  }
}

// A random block system with 4 blocks chained by "overlaps" 0-1, 1-2, 2-3.
BlockNormalEquations
randomBlockSystem(unsigned seed, bool flat_block_2)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  BlockNormalEquations ne(4);
  for (int i = 0; i < 3; ++i) {
    PairNormalEquations pair;
    for (int r = 0; r < 60; ++r) {
      PairNormalEquations::Row a;
      for (int c = 0; c < 14; ++c)
        a[c] = g(rng);
      if (flat_block_2 && i == 1)
        a[7 + TX] = a[7 + TY] = 0.0;  // block 2 seen only through its first overlap ...
      if (flat_block_2 && i == 2)
        a[TX] = a[TY] = 0.0;  // ... and its second: tx, ty of block 2 undeterminable
      pair.add(a, g(rng), 1.0);
    }
    pair.symmetrize();
    ne.addOverlap(i, i + 1, pair);
  }
  return ne;
}

TEST(BlockNormalEquations, SparseAndDenseSolvesAgree)
{
  const BlockNormalEquations ne = randomBlockSystem(5, false);
  EXPECT_EQ(ne.nonZeroBlocks(), 4u + 3u);
  GaussMarkovProblem problem(28);
  problem.apriori_weights.head<7>().setConstant(kInf);
  problem.apriori_weights[7 + TZ] = 2.0;  // one soft constraint
  problem.apriori_values[7 + TZ] = 0.3;
  const GaussMarkovSolution dense = solveGaussMarkov(ne, problem);
  const GaussMarkovSolution sparse = solveGaussMarkov(ne, problem, 0);
  ASSERT_TRUE(dense.ok && sparse.ok);
  EXPECT_LT((dense.dx - sparse.dx).norm(), 1e-10 * dense.dx.norm());
  EXPECT_LT((dense.qxx - sparse.qxx).norm(), 1e-10 * dense.qxx.norm());
  EXPECT_NEAR(dense.sigma0, sparse.sigma0, 1e-12);
  EXPECT_EQ(dense.redundancy, 180 + 1 - 21);
  // Independent: the dense normal matrix solved directly (block 0 eliminated).
  const Eigen::MatrixXd N = ne.denseMatrix().bottomRightCorner(21, 21);
  Eigen::MatrixXd Ne = N;
  Eigen::VectorXd b = ne.rhs().tail(21);
  Ne(TZ, TZ) += 2.0;
  b[TZ] += 2.0 * (0.0 - 0.3);
  const Eigen::VectorXd dx = -Ne.ldlt().solve(b);
  EXPECT_LT((dense.dx.tail(21) - dx).norm(), 1e-10 * dx.norm());
}

TEST(BlockNormalEquations, BothSolvesFlagTheUndeterminableParametersOfAFlatBlock)
{
  const BlockNormalEquations ne = randomBlockSystem(6, true);
  GaussMarkovProblem problem(28);
  problem.apriori_weights.head<7>().setConstant(kInf);
  for (const Eigen::Index limit : {Eigen::Index(700), Eigen::Index(0)}) {
    const GaussMarkovSolution s = solveGaussMarkov(ne, problem, limit);
    ASSERT_TRUE(s.ok) << s.message;
    EXPECT_FALSE(s.determinable[14 + TX]) << "dense limit " << limit;
    EXPECT_FALSE(s.determinable[14 + TY]) << "dense limit " << limit;
    EXPECT_TRUE(s.determinable[14 + TZ]);
    EXPECT_EQ(s.unknowns, 19);
    EXPECT_EQ(s.dx[14 + TX], 0.0);
  }
}

}  // namespace
