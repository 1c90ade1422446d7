// The score test of held-out parameters (omitted_parameters.h) against independent computations
// on a linear model, where one Gauss–Newton step from the restricted solution is the full
// model's least-squares solution: the estimate must equal the full refit, its formal σ the full
// model's σ0 √Q_OO, its sandwich σ the full model's (Q M Q)_OO for the same middle term, and
// under a true restricted model z must be standard normal.
#include <pcl_ls3d/adjustment/omitted_parameters.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using pcl_ls3d::MiddleTermFn;
using pcl_ls3d::OmittedParameterTest;
using pcl_ls3d::testOmittedParameters;

namespace {

// y = A β + e, with the last `held` columns held at 0 in the restricted fit.
struct LinearProblem
{
  Eigen::MatrixXd A;
  Eigen::VectorXd y;
};

LinearProblem
makeProblem(std::mt19937& rng, int n, const Eigen::VectorXd& beta, double sigma)
{
  std::normal_distribution<double> g(0.0, 1.0);
  LinearProblem p;
  p.A.resize(n, beta.size());
  p.y.resize(n);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < beta.size(); ++c)
      p.A(i, c) = g(rng) + (c == 3 ? 0.5 * p.A(i, 0) : 0.0);  // the held-out column correlates with column 0
    p.y[i] = p.A.row(i).dot(beta) + sigma * g(rng);
  }
  return p;
}

// The restricted solution's normal equations in the adjustment's convention V = A X + L
// (L = −y), its Q padded with zeros, gradient AᵀV at the solution and σ0.
struct Restricted
{
  Eigen::MatrixXd N, qxx;
  Eigen::VectorXd gradient;
  double sigma0 = 0.0;
};

Restricted
restrictedFit(const LinearProblem& p, int estimated)
{
  const Eigen::Index u = p.A.cols(), n = p.A.rows();
  const Eigen::MatrixXd AE = p.A.leftCols(estimated);
  const Eigen::MatrixXd QE = (AE.transpose() * AE).inverse();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(u);
  x.head(estimated) = QE * AE.transpose() * p.y;
  const Eigen::VectorXd v = p.A * x - p.y;
  Restricted r;
  r.N = p.A.transpose() * p.A;
  r.qxx = Eigen::MatrixXd::Zero(u, u);
  r.qxx.topLeftCorner(estimated, estimated) = QE;
  r.gradient = p.A.transpose() * v;
  r.sigma0 = std::sqrt(v.squaredNorm() / static_cast<double>(n - estimated));
  return r;
}

// A middle term that ignores the step: M itself.
MiddleTermFn
fixedMiddle(const Eigen::MatrixXd& M)
{
  return [M](const Eigen::VectorXd&, const Eigen::MatrixXd&) { return M; };
}

}  // namespace

TEST(OmittedParameters, EstimateAndFormalSigmaEqualTheFullRefit)
{
  std::mt19937 rng(7);
  const Eigen::VectorXd beta = (Eigen::VectorXd(5) << 1.0, -2.0, 0.5, 0.3, -0.2).finished();
  const LinearProblem p = makeProblem(rng, 400, beta, 0.1);
  const Restricted r = restrictedFit(p, 3);
  const Eigen::MatrixXd formal_middle = r.sigma0 * r.sigma0 * r.N;
  const OmittedParameterTest t =
      testOmittedParameters(r.N, r.gradient, r.qxx, fixedMiddle(formal_middle), r.sigma0, {3, 4});
  ASSERT_TRUE(t.ok) << t.message;
  ASSERT_EQ(t.parameters.size(), 2u);
  // Independent: the full least-squares solution and its inverse normal matrix.
  const Eigen::MatrixXd Qfull = r.N.inverse();
  const Eigen::VectorXd full = Qfull * p.A.transpose() * p.y;
  for (int k = 0; k < 2; ++k) {
    const auto& q = t.parameters[static_cast<std::size_t>(k)];
    EXPECT_EQ(q.index, 3 + k);
    EXPECT_NEAR(q.estimate, full[3 + k], 1e-9);
    EXPECT_NEAR(q.sigma_formal, r.sigma0 * std::sqrt(Qfull(3 + k, 3 + k)), 1e-12);
    EXPECT_NEAR(q.sigma, q.sigma_formal, 1e-12);  // the middle term is the formal one
    EXPECT_NEAR(q.z, q.estimate / q.sigma, 1e-12);
  }
  // The truth is far from 0 in σ: the held-out columns are highly significant.
  EXPECT_GT(std::abs(t.parameters[0].z), 10.0);
  EXPECT_GT(t.statistic, 100.0);
}

TEST(OmittedParameters, SandwichSigmaIsTheFullModelsSandwichForTheSameMiddleTerm)
{
  std::mt19937 rng(11);
  const Eigen::VectorXd beta = (Eigen::VectorXd(4) << 1.0, -2.0, 0.5, 0.0).finished();
  const LinearProblem p = makeProblem(rng, 300, beta, 0.1);
  const Restricted r = restrictedFit(p, 3);
  // A middle term well above the formal one (correlated errors would give such).
  Eigen::MatrixXd M = 3.0 * r.sigma0 * r.sigma0 * r.N;
  M += 0.01 * Eigen::MatrixXd::Ones(4, 4);
  const OmittedParameterTest t = testOmittedParameters(r.N, r.gradient, r.qxx, fixedMiddle(M), r.sigma0, {3});
  ASSERT_TRUE(t.ok) << t.message;
  const Eigen::MatrixXd Qfull = r.N.inverse();
  const double expected = std::sqrt((Qfull * M * Qfull)(3, 3));
  EXPECT_NEAR(t.parameters[0].sigma, expected, 1e-12 * expected);
  EXPECT_GT(t.parameters[0].sigma, 1.5 * t.parameters[0].sigma_formal);
  EXPECT_NEAR(t.statistic, t.parameters[0].z * t.parameters[0].z, 1e-9);
}

// The middle term is asked for the freed model's one-step residuals: with White's (HC0) middle
// term Σ a aᵀ (v + a·step)² the σ is exactly the full refit's HC0 sandwich σ, computed here from
// the full refit's own residuals (on a linear model the one-step is the refit).
TEST(OmittedParameters, MiddleTermSeesTheFreedResiduals)
{
  std::mt19937 rng(13);
  const Eigen::VectorXd beta = (Eigen::VectorXd(4) << 1.0, -2.0, 0.5, 0.8).finished();
  const LinearProblem p = makeProblem(rng, 300, beta, 0.1);
  const Restricted r = restrictedFit(p, 3);
  const MiddleTermFn hc0 = [&](const Eigen::VectorXd& step, const Eigen::MatrixXd&) {
    // Residuals v = A X − y at the restricted solution x (zero in O) moved on by the step.
    const Eigen::VectorXd x = r.qxx * p.A.transpose() * p.y;
    const Eigen::VectorXd res = p.A * (x + step) - p.y;
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(4, 4);
    for (Eigen::Index i = 0; i < p.A.rows(); ++i)
      M += p.A.row(i).transpose() * p.A.row(i) * res[i] * res[i];
    return M;
  };
  const OmittedParameterTest t = testOmittedParameters(r.N, r.gradient, r.qxx, hc0, r.sigma0, {3});
  ASSERT_TRUE(t.ok) << t.message;
  const Eigen::MatrixXd Qfull = r.N.inverse();
  const Eigen::VectorXd full = Qfull * p.A.transpose() * p.y;
  const Eigen::VectorXd res = p.A * full - p.y;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(4, 4);
  for (Eigen::Index i = 0; i < p.A.rows(); ++i)
    M += p.A.row(i).transpose() * p.A.row(i) * res[i] * res[i];
  const double expected = std::max(std::sqrt((Qfull * M * Qfull)(3, 3)), t.parameters[0].sigma_formal);
  EXPECT_NEAR(t.parameters[0].sigma, expected, 1e-9 * expected);
  EXPECT_NEAR(t.parameters[0].estimate, full[3], 1e-9);
}

TEST(OmittedParameters, UnderATrueRestrictedModelZIsStandardNormal)
{
  std::mt19937 rng(3);
  const Eigen::VectorXd beta = (Eigen::VectorXd(4) << 0.3, 1.0, -0.7, 0.0).finished();
  int beyond_196 = 0, beyond_3 = 0;
  const int trials = 2000;
  for (int k = 0; k < trials; ++k) {
    const LinearProblem p = makeProblem(rng, 60, beta, 0.2);
    const Restricted r = restrictedFit(p, 3);
    const OmittedParameterTest t =
        testOmittedParameters(r.N, r.gradient, r.qxx, fixedMiddle(r.sigma0 * r.sigma0 * r.N), r.sigma0, {3});
    ASSERT_TRUE(t.ok);
    beyond_196 += std::abs(t.parameters[0].z) > 1.96;
    beyond_3 += std::abs(t.parameters[0].z) > 3.0;
  }
  // 5 % and 0.27 % expected (t with 57 dof: 5.3 %, 0.4 %); binomial 3σ bands.
  EXPECT_GT(beyond_196, 0.053 * trials - 3.0 * std::sqrt(0.053 * 0.947 * trials));
  EXPECT_LT(beyond_196, 0.053 * trials + 3.0 * std::sqrt(0.053 * 0.947 * trials));
  EXPECT_LT(beyond_3, 20);
}

TEST(OmittedParameters, RefusesWhatCannotBeTested)
{
  std::mt19937 rng(5);
  const Eigen::VectorXd beta = (Eigen::VectorXd(4) << 1.0, -2.0, 0.5, 0.0).finished();
  LinearProblem p = makeProblem(rng, 100, beta, 0.1);
  Restricted r = restrictedFit(p, 3);
  const MiddleTermFn M = fixedMiddle(r.sigma0 * r.sigma0 * r.N);
  // An estimated parameter is no held-out one.
  EXPECT_FALSE(testOmittedParameters(r.N, r.gradient, r.qxx, M, r.sigma0, {1}).ok);
  EXPECT_FALSE(testOmittedParameters(r.N, r.gradient, r.qxx, M, r.sigma0, {}).ok);
  EXPECT_FALSE(testOmittedParameters(r.N, r.gradient, r.qxx, M, r.sigma0, {7}).ok);
  // A held-out column the observations never see carries no information.
  p.A.col(3).setZero();
  r = restrictedFit(p, 3);
  const OmittedParameterTest t = testOmittedParameters(r.N, r.gradient, r.qxx, M, r.sigma0, {3});
  EXPECT_FALSE(t.ok);
  EXPECT_FALSE(t.message.empty());
  // Non-finite input.
  Eigen::VectorXd g = r.gradient;
  g[0] = std::nan("");
  EXPECT_FALSE(testOmittedParameters(r.N, g, r.qxx, M, r.sigma0, {3}).ok);
}
