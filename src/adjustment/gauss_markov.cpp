#include <pcl_ls3d/adjustment/gauss_markov.h>

#include "gauss_markov_steps.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <vector>

namespace pcl_ls3d {

namespace {

using namespace detail;

template <typename Matrix>
Eigen::MatrixXd
subMatrix(const Matrix& M, const std::vector<int>& idx)
{
  const int k = static_cast<int>(idx.size());
  Eigen::MatrixXd S(k, k);
  for (int r = 0; r < k; ++r)
    for (int c = 0; c < k; ++c)
      S(r, c) = M(idx[static_cast<std::size_t>(r)], idx[static_cast<std::size_t>(c)]);
  return S;
}

// Rank test on the scaled reduced normal matrix: while its smallest eigenvalue is below
// threshold × largest, the parameter dominating that eigenvector is undeterminable.
template <typename Matrix>
void
removeUndeterminable(const Matrix& N, const Eigen::VectorXd& scaling, double threshold,
                     std::vector<bool>& estimated)
{
  for (;;) {
    const std::vector<int> idx = indicesOf(estimated);
    if (idx.empty())
      return;
    Eigen::MatrixXd S = subMatrix(N, idx);
    for (std::size_t r = 0; r < idx.size(); ++r)
      for (std::size_t c = 0; c < idx.size(); ++c)
        S(static_cast<int>(r), static_cast<int>(c)) *= scaling[idx[r]] * scaling[idx[c]];
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(S);
    if (es.info() != Eigen::Success)
      return;
    const double largest = es.eigenvalues().cwiseAbs().maxCoeff();
    const double smallest = es.eigenvalues()[0];  // ascending order
    if (largest > 0.0 && std::isfinite(largest) && smallest > threshold * largest)
      return;
    Eigen::Index worst = 0;
    es.eigenvectors().col(0).cwiseAbs().maxCoeff(&worst);
    estimated[static_cast<std::size_t>(idx[static_cast<std::size_t>(worst)])] = false;
  }
}

// Adds the a-priori observations (eq. 9) to N and b; marks fixed parameters.
template <typename Matrix, typename Vector>
void
addAprioriObservations(const GaussMarkovProblem& problem, Matrix& N, Vector& b, GaussMarkovSolution& sol,
                       std::vector<bool>& estimated)
{
  const Eigen::VectorXd& pe = problem.apriori_weights;
  for (Eigen::Index i = 0; i < N.rows(); ++i) {
    const std::size_t s = static_cast<std::size_t>(i);
    sol.fixed[s] = std::isinf(pe[i]);
    estimated[s] = !std::isinf(pe[i]);
    if (!std::isinf(pe[i]) && pe[i] > 0.0) {
      N(i, i) += pe[i];
      b[i] += pe[i] * (problem.current[i] - problem.apriori_values[i]);  // L_e at X0
    }
  }
}

// The solve on Eigen storage of either fixed (7: bit-identical to the pair engine's history)
// or dynamic size.
template <typename Matrix, typename Vector>
GaussMarkovSolution
solve(const Matrix& N0, const Vector& b0, double ltpl, std::size_t n, const GaussMarkovProblem& problem)
{
  const Eigen::Index u = N0.rows();
  GaussMarkovSolution sol;
  sol.dx = Eigen::VectorXd::Zero(u);
  sol.qxx = Eigen::MatrixXd::Zero(u, u);
  sol.fixed.assign(static_cast<std::size_t>(u), false);
  sol.determinable.assign(static_cast<std::size_t>(u), false);
  Matrix N = N0;
  Vector b = b0;
  std::vector<bool> estimated(static_cast<std::size_t>(u), false);
  addAprioriObservations(problem, N, b, sol, estimated);
  if (indicesOf(estimated).empty()) {
    sol.message = "every parameter is fixed: nothing to estimate";
    return sol;
  }
  removeUndeterminable(N, problem.scaling, problem.determinability_threshold, estimated);
  const std::vector<int> idx = indicesOf(estimated);
  if (idx.empty()) {
    sol.message = "the geometry determines none of the free parameters (singular normal matrix)";
    return sol;
  }
  const int k = static_cast<int>(idx.size());
  Eigen::VectorXd br(k);
  for (int r = 0; r < k; ++r)
    br[r] = b[idx[static_cast<std::size_t>(r)]];
  Eigen::LDLT<Eigen::MatrixXd> ldlt(subMatrix(N, idx));
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) {
    sol.message = "reduced normal matrix is not positive definite";
    return sol;
  }
  const Eigen::VectorXd dxr = -ldlt.solve(br);                             // eq. 10
  const Eigen::MatrixXd Qr = ldlt.solve(Eigen::MatrixXd::Identity(k, k));  // eq. 14
  if (!dxr.allFinite() || !Qr.allFinite()) {
    sol.message = "solve produced non-finite values";
    return sol;
  }
  Vector dx = Vector::Zero(u);
  for (int r = 0; r < k; ++r) {
    const int i = idx[static_cast<std::size_t>(r)];
    dx[i] = dxr[r];
    for (int c = 0; c < k; ++c)
      sol.qxx(i, idx[static_cast<std::size_t>(c)]) = Qr(r, c);
  }
  sol.dx = dx;
  sol.determinable = estimated;
  sol.unknowns = k;
  fillResidualStatistics(N0, b0, ltpl, n, dx, idx, problem, sol);
  sol.ok = true;
  return sol;
}

bool
consistent(const Eigen::MatrixXd& N, const Eigen::VectorXd& b, const GaussMarkovProblem& p)
{
  const Eigen::Index u = N.rows();
  return u > 0 && N.cols() == u && b.size() == u && p.current.size() == u && p.apriori_values.size() == u &&
         p.apriori_weights.size() == u && p.scaling.size() == u;
}

}  // namespace

GaussMarkovProblem::GaussMarkovProblem(int unknowns)
    : current(Eigen::VectorXd::Zero(unknowns)), apriori_values(Eigen::VectorXd::Zero(unknowns)),
      apriori_weights(Eigen::VectorXd::Zero(unknowns)), scaling(Eigen::VectorXd::Ones(unknowns))
{}

GaussMarkovSolution
solveGaussMarkov(const Eigen::MatrixXd& N, const Eigen::VectorXd& b, double ltpl, std::size_t n,
                 const GaussMarkovProblem& problem)
{
  if (!consistent(N, b, problem)) {
    GaussMarkovSolution sol;
    sol.message = "normal equations and problem differ in size";
    return sol;
  }
  if (N.rows() == 7)  // one parameter block: fixed-size arithmetic
    return solve(Matrix7d(N), Vector7d(b), ltpl, n, problem);
  return solve(N, b, ltpl, n, problem);
}

}  // namespace pcl_ls3d
