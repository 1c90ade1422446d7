#include <pcl_ls3d/adjustment/gauss_markov.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <vector>

namespace pcl_ls3d {

namespace {

std::vector<int>
indicesOf(const std::array<bool, 7>& mask)
{
  std::vector<int> idx;
  for (int i = 0; i < 7; ++i)
    if (mask[static_cast<std::size_t>(i)])
      idx.push_back(i);
  return idx;
}

Eigen::MatrixXd
subMatrix(const Matrix7d& M, const std::vector<int>& idx)
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
void
removeUndeterminable(const Matrix7d& N, const Vector7d& scaling, double threshold,
                     std::array<bool, 7>& estimated)
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

}  // namespace

GaussMarkovSolution
solveGaussMarkov(const NormalEquations& ne, const GaussMarkovProblem& problem)
{
  GaussMarkovSolution sol;
  const Vector7d& pe = problem.apriori_weights;
  // L_e of eq. 9 at the current estimate: V_e = dx + (X0 − L_e).
  const Vector7d le = problem.current - problem.apriori_values;

  Matrix7d N = ne.N;
  Vector7d b = ne.b;
  std::array<bool, 7> estimated{};
  for (int i = 0; i < 7; ++i) {
    sol.fixed[static_cast<std::size_t>(i)] = std::isinf(pe[i]);
    estimated[static_cast<std::size_t>(i)] = !std::isinf(pe[i]);
    if (!std::isinf(pe[i]) && pe[i] > 0.0) {
      N(i, i) += pe[i];
      b[i] += pe[i] * le[i];
    }
  }
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

  const Eigen::MatrixXd Nr = subMatrix(N, idx);
  const int k = static_cast<int>(idx.size());
  Eigen::VectorXd br(k);
  for (int r = 0; r < k; ++r)
    br[r] = b[idx[static_cast<std::size_t>(r)]];
  Eigen::LDLT<Eigen::MatrixXd> ldlt(Nr);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) {
    sol.message = "reduced normal matrix is not positive definite";
    return sol;
  }
  const Eigen::VectorXd dxr = -ldlt.solve(br);                              // eq. 10
  const Eigen::MatrixXd Qr = ldlt.solve(Eigen::MatrixXd::Identity(k, k));  // eq. 14
  if (!dxr.allFinite() || !Qr.allFinite()) {
    sol.message = "solve produced non-finite values";
    return sol;
  }
  for (int r = 0; r < k; ++r) {
    const int i = idx[static_cast<std::size_t>(r)];
    sol.dx[i] = dxr[r];
    for (int c = 0; c < k; ++c)
      sol.qxx(i, idx[static_cast<std::size_t>(c)]) = Qr(r, c);
  }
  sol.determinable = estimated;
  sol.unknowns = k;

  // VᵀPV = LᵀPL + 2 dxᵀ AᵀPL + dxᵀ AᵀPA dx (eq. 12 without storing V).
  sol.vtpv = std::max(0.0, ne.ltpl + 2.0 * sol.dx.dot(ne.b) + sol.dx.dot(ne.N * sol.dx));
  for (int i : idx)
    if (pe[i] > 0.0) {
      const double ve = sol.dx[i] + le[i];  // eq. 13
      sol.vetpve += pe[i] * ve * ve;
      ++sol.soft_constraints;
    }
  sol.redundancy = static_cast<long>(ne.n) + sol.soft_constraints - sol.unknowns;
  if (sol.redundancy > 0)
    sol.sigma0 = std::sqrt((sol.vtpv + sol.vetpve) / static_cast<double>(sol.redundancy));
  sol.ok = true;
  return sol;
}

}  // namespace pcl_ls3d
