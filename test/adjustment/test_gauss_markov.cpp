// The Gauss–Markoff solve (Zuo et al. 2012, eqs. 9–14) against an independent dense least-squares
// computation, plus fixed/soft a-priori observations, the rank test and the Jacobian.
#include <pcl_ls3d/adjustment/block_normal_equations.h>
#include <pcl_ls3d/adjustment/gauss_markov.h>
#include <pcl_ls3d/adjustment/similarity_jacobian.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl_ls3d;

namespace {
struct LinearProblem
{
  Eigen::MatrixXd A;
  Eigen::VectorXd l;
  NormalEquations ne;
};

LinearProblem
randomProblem(int n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  LinearProblem p;
  p.A.resize(n, 7);
  p.l.resize(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < 7; ++j)
      p.A(i, j) = g(rng);
    p.l[i] = g(rng);
    p.ne.add(p.A.row(i), p.l[i], 1.0);
  }
  p.ne.symmetrize();
  return p;
}
}  // namespace

TEST(GaussMarkov, MatchesDenseLeastSquares)
{
  const LinearProblem p = randomProblem(200, 1);
  const GaussMarkovSolution s = solveGaussMarkov(p.ne, GaussMarkovProblem());
  ASSERT_TRUE(s.ok) << s.message;
  // Independent: minimise |A dx + l|² by QR.
  const Eigen::VectorXd dx = p.A.colPivHouseholderQr().solve(-p.l);
  const Eigen::VectorXd v = p.A * dx + p.l;
  const Eigen::MatrixXd Q = (p.A.transpose() * p.A).inverse();
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(s.dx[i], dx[i], 1e-10);
    for (int j = 0; j < 7; ++j)
      EXPECT_NEAR(s.qxx(i, j), Q(i, j), 1e-12);
  }
  EXPECT_EQ(s.redundancy, 200 - 7);
  EXPECT_NEAR(s.sigma0, std::sqrt(v.squaredNorm() / 193.0), 1e-10);  // eq. 11
}

TEST(GaussMarkov, FixedParameterIsEliminatedExactly)
{
  const LinearProblem p = randomProblem(100, 2);
  GaussMarkovProblem gp;
  gp.apriori_weights[OMEGA] = std::numeric_limits<double>::infinity();
  const GaussMarkovSolution s = solveGaussMarkov(p.ne, gp);
  ASSERT_TRUE(s.ok);
  EXPECT_EQ(s.dx[OMEGA], 0.0);
  EXPECT_TRUE(s.fixed[OMEGA]);
  EXPECT_FALSE(s.determinable[OMEGA]);
  EXPECT_EQ(s.qxx.row(OMEGA).norm(), 0.0);
  // Independent: drop the column.
  Eigen::MatrixXd A6(p.A.rows(), 6);
  A6 << p.A.leftCols(OMEGA), p.A.rightCols(6 - OMEGA);
  const Eigen::VectorXd dx6 = A6.colPivHouseholderQr().solve(-p.l);
  EXPECT_NEAR(s.dx[TX], dx6[0], 1e-10);
  EXPECT_NEAR(s.dx[SCALE], dx6[5], 1e-10);
  EXPECT_EQ(s.redundancy, 100 - 6);
}

TEST(GaussMarkov, SoftConstraintEqualsAugmentedSystem)
{
  const LinearProblem p = randomProblem(50, 3);
  GaussMarkovProblem gp;
  gp.current[TZ] = 0.2;
  gp.apriori_values[TZ] = 0.5;
  gp.apriori_weights[TZ] = 4.0;  // σ_e = σ0 / 2
  const GaussMarkovSolution s = solveGaussMarkov(p.ne, gp);
  ASSERT_TRUE(s.ok);
  // Independent: one extra row 2·(dx_tz + (0.2 − 0.5)) (weight 4 = 2²).
  Eigen::MatrixXd A(51, 7);
  Eigen::VectorXd l(51);
  A.topRows(50) = p.A;
  l.head(50) = p.l;
  A.row(50).setZero();
  A(50, TZ) = 2.0;
  l[50] = 2.0 * (0.2 - 0.5);
  const Eigen::VectorXd dx = A.colPivHouseholderQr().solve(-l);
  for (int i = 0; i < 7; ++i)
    EXPECT_NEAR(s.dx[i], dx[i], 1e-10);
  EXPECT_EQ(s.redundancy, 51 - 7);
  EXPECT_NEAR(s.sigma0, std::sqrt((A * dx + l).squaredNorm() / 44.0), 1e-10);
}

TEST(GaussMarkov, RankTestFlagsUndeterminableParameters)
{
  LinearProblem p = randomProblem(100, 4);
  // Columns tx and ty carry no information (a flat plane seen along z).
  NormalEquations ne;
  for (int i = 0; i < 100; ++i) {
    RowVector7d a = p.A.row(i);
    a[TX] = 0.0;
    a[TY] = 0.0;
    ne.add(a, p.l[i], 1.0);
  }
  ne.symmetrize();
  const GaussMarkovSolution s = solveGaussMarkov(ne, GaussMarkovProblem());
  ASSERT_TRUE(s.ok) << s.message;
  EXPECT_FALSE(s.determinable[TX]);
  EXPECT_FALSE(s.determinable[TY]);
  EXPECT_TRUE(s.determinable[TZ]);
  EXPECT_EQ(s.dx[TX], 0.0);
  EXPECT_EQ(s.unknowns, 5);
  // Nothing determinable at all: refused.
  const GaussMarkovSolution none = solveGaussMarkov(NormalEquations(), GaussMarkovProblem());
  EXPECT_FALSE(none.ok);
}

TEST(SimilarityJacobian, MatchesFiniteDifferences)
{
  SimilarityTransform X;
  X.t = Eigen::Vector3d(1, -2, 0.5);
  X.phi = 0.1;
  X.omega = -0.2;
  X.kappa = 0.3;
  X.m = 1.01;
  const Eigen::Vector3d x(3.0, -4.0, 2.0);
  const SimilarityLinearization lin(X);
  const Matrix37d J = lin.jacobian(x);
  const double h = 1e-6;
  for (int j = 0; j < 7; ++j) {
    Vector7d p = X.vector(), q = X.vector();
    p[j] += h;
    q[j] -= h;
    const Eigen::Vector3d fd = (SimilarityTransform(p).apply(x) - SimilarityTransform(q).apply(x)) / (2 * h);
    EXPECT_LT((J.col(j) - fd).norm(), 1e-7) << "column " << j;  // central differences, O(h²)
  }
  EXPECT_LT((lin.apply(x) - X.apply(x)).norm(), 1e-12);
  const Eigen::Vector3d u = Eigen::Vector3d(1, 2, 2) / 3.0;
  EXPECT_LT((lin.designRow(u, x) - u.transpose() * J).norm(), 1e-12);
}

namespace {
// The recorded system: "key v1 v2 ..." lines (hexfloat), repeated keys append.
std::map<std::string, std::vector<double>>
readRecord(const std::string& path)
{
  std::map<std::string, std::vector<double>> record;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#')
      continue;
    std::istringstream words(line);
    std::string key, value;
    words >> key;
    while (words >> value)
      record[key].push_back(std::strtod(value.c_str(), nullptr));
  }
  return record;
}

template <typename Vector>
void
fill(Vector& v, const std::vector<double>& values)
{
  for (Eigen::Index i = 0; i < v.size(); ++i)
    v[i] = values[static_cast<std::size_t>(i)];
}
}  // namespace

// The generic solve with one parameter block reproduces, bit for bit, the 7-parameter solve of
// the engine before it was split into stages (commit 2c7a1cc), on normal equations recorded from
// a generated pair with a fixed scale and a soft height constraint (test/data/gauss_markov_2c7a1cc.txt).
TEST(GaussMarkov, GenericSolveEqualsTheRecordedPairSolveBitForBit)
{
  const auto r = readRecord(PCL_LS3D_TEST_SOURCE_DIR "/data/gauss_markov_2c7a1cc.txt");
  ASSERT_EQ(r.count("N") ? r.at("N").size() : 0u, 49u) << "recorded system missing";
  NormalEquations ne;
  Eigen::Map<const Eigen::Matrix<double, 7, 7, Eigen::RowMajor>> N(r.at("N").data());
  ne.N = N;
  fill(ne.b, r.at("b"));
  ne.ltpl = r.at("ltpl")[0];
  ne.n = static_cast<std::size_t>(r.at("n")[0]);
  GaussMarkovProblem gp;
  fill(gp.current, r.at("current"));
  fill(gp.apriori_values, r.at("apriori_values"));
  fill(gp.apriori_weights, r.at("apriori_weights"));
  fill(gp.scaling, r.at("scaling"));
  gp.determinability_threshold = r.at("threshold")[0];
  BlockNormalEquations one_block(1);
  one_block.addBlock(0, ne);

  for (const GaussMarkovSolution& s : {solveGaussMarkov(ne, gp), solveGaussMarkov(one_block, gp)}) {
    ASSERT_TRUE(s.ok) << s.message;
    Eigen::Map<const Eigen::Matrix<double, 7, 7, Eigen::RowMajor>> qxx(r.at("qxx").data());
    for (int i = 0; i < 7; ++i) {
      EXPECT_EQ(s.dx[i], r.at("dx")[static_cast<std::size_t>(i)]) << "dx " << i;
      for (int j = 0; j < 7; ++j)
        EXPECT_EQ(s.qxx(i, j), qxx(i, j)) << "qxx " << i << "," << j;
    }
    EXPECT_EQ(s.vtpv, r.at("vtpv")[0]);
    EXPECT_EQ(s.vetpve, r.at("vetpve")[0]);
    EXPECT_EQ(s.sigma0, r.at("sigma0")[0]);
    EXPECT_EQ(static_cast<double>(s.redundancy), r.at("redundancy")[0]);
    EXPECT_EQ(static_cast<double>(s.unknowns), r.at("unknowns")[0]);
  }
}
