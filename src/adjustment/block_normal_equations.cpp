#include <pcl_ls3d/adjustment/block_normal_equations.h>

#include "gauss_markov_steps.h"

#include <Eigen/SparseCholesky>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace pcl_ls3d {

using detail::indicesOf;

BlockNormalEquations::BlockNormalEquations(int blocks)
    : blocks_(blocks), b_(Eigen::VectorXd::Zero(7 * static_cast<Eigen::Index>(blocks)))
{}

void
BlockNormalEquations::addToBlock(int i, int j, const Matrix7d& value)
{
  auto it = upper_.find({i, j});
  if (it == upper_.end())
    upper_.emplace(std::make_pair(i, j), value);
  else
    it->second += value;
}

void
BlockNormalEquations::addOverlap(int i, int j, const PairNormalEquations& c)
{
  if (i == j) {  // both rows on one block: the sum of the two halves
    NormalEquations single;
    single.N = c.N.topLeftCorner<7, 7>() + c.N.topRightCorner<7, 7>() + c.N.bottomLeftCorner<7, 7>() +
               c.N.bottomRightCorner<7, 7>();
    single.b = c.b.head<7>() + c.b.tail<7>();
    single.ltpl = c.ltpl;
    single.n = c.n;
    addBlock(i, single);
    return;
  }
  const bool swap = i > j;
  const int lo = swap ? j : i, hi = swap ? i : j;
  addToBlock(i, i, c.N.topLeftCorner<7, 7>());
  addToBlock(j, j, c.N.bottomRightCorner<7, 7>());
  addToBlock(lo, hi, swap ? Matrix7d(c.N.bottomLeftCorner<7, 7>()) : Matrix7d(c.N.topRightCorner<7, 7>()));
  b_.segment<7>(7 * i) += c.b.head<7>();
  b_.segment<7>(7 * j) += c.b.tail<7>();
  ltpl_ += c.ltpl;
  n_ += c.n;
}

void
BlockNormalEquations::addBlock(int i, const NormalEquations& c)
{
  addToBlock(i, i, c.N);
  b_.segment<7>(7 * i) += c.b;
  ltpl_ += c.ltpl;
  n_ += c.n;
}

BlockNormalEquations&
BlockNormalEquations::operator+=(const BlockNormalEquations& other)
{
  for (const auto& kv : other.upper_)
    addToBlock(kv.first.first, kv.first.second, kv.second);
  b_ += other.b_;
  ltpl_ += other.ltpl_;
  n_ += other.n_;
  return *this;
}

Eigen::SparseMatrix<double>
BlockNormalEquations::sparseMatrix() const
{
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(upper_.size() * 98);
  for (const auto& kv : upper_) {
    const int i = kv.first.first, j = kv.first.second;
    for (int r = 0; r < 7; ++r)
      for (int c = 0; c < 7; ++c) {
        entries.emplace_back(7 * i + r, 7 * j + c, kv.second(r, c));
        if (i != j)
          entries.emplace_back(7 * j + c, 7 * i + r, kv.second(r, c));
      }
  }
  Eigen::SparseMatrix<double> N(unknowns(), unknowns());
  N.setFromTriplets(entries.begin(), entries.end());
  return N;
}

Eigen::MatrixXd
BlockNormalEquations::denseMatrix() const
{
  return Eigen::MatrixXd(sparseMatrix());
}

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Scaled reduced matrix S = D N_r D over the estimated parameters (D = scaling).
SparseMatrix
scaledReduced(const SparseMatrix& N, const std::vector<int>& idx, const Eigen::VectorXd& scaling)
{
  std::vector<int> position(static_cast<std::size_t>(N.rows()), -1);
  for (std::size_t r = 0; r < idx.size(); ++r)
    position[static_cast<std::size_t>(idx[r])] = static_cast<int>(r);
  std::vector<Eigen::Triplet<double>> entries;
  for (int col = 0; col < N.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(N, col); it; ++it) {
      const int r = position[static_cast<std::size_t>(it.row())], c = position[static_cast<std::size_t>(col)];
      if (r >= 0 && c >= 0)
        entries.emplace_back(r, c, it.value() * scaling[it.row()] * scaling[col]);
    }
  const auto k = static_cast<Eigen::Index>(idx.size());
  SparseMatrix S(k, k);
  S.setFromTriplets(entries.begin(), entries.end());
  return S;
}

// The estimated parameter with the smallest relative pivot D_kk / S_kk below the threshold,
// or −1 when every pivot passes.
int
weakestPivot(const Eigen::SimplicialLDLT<SparseMatrix>& ldlt, const SparseMatrix& S, double threshold)
{
  const Eigen::VectorXd D = ldlt.vectorD();
  const auto& order = ldlt.permutationPinv().indices();  // factor row k = original row order[k]
  const double largest = S.diagonal().cwiseAbs().maxCoeff();
  int worst = -1;
  double worst_ratio = threshold;
  for (Eigen::Index k = 0; k < D.size(); ++k) {
    const int original = order[k];
    const double diagonal = S.coeff(original, original);
    double ratio = diagonal > threshold * largest ? D[k] / diagonal : 0.0;
    if (std::isnan(ratio))
      ratio = 0.0;
    if (ratio < worst_ratio) {
      worst = original;
      worst_ratio = ratio;
    }
  }
  return worst;
}

// Held parameters (infinite a-priori weight) are fixed; the others' a-priori observations
// enter N and b.
void
addAprioriObservations(const GaussMarkovProblem& problem, SparseMatrix& N, Eigen::VectorXd& b,
                       std::vector<bool>& fixed, std::vector<bool>& estimated)
{
  const Eigen::VectorXd& pe = problem.apriori_weights;
  for (Eigen::Index i = 0; i < N.rows(); ++i) {
    const std::size_t s = static_cast<std::size_t>(i);
    fixed[s] = std::isinf(pe[i]);
    estimated[s] = !fixed[s];
    if (estimated[s] && pe[i] > 0.0) {
      N.coeffRef(i, i) += pe[i];
      b[i] += pe[i] * (problem.current[i] - problem.apriori_values[i]);
    }
  }
}

// Rank test: drops the weakest pivot from `estimated` until all pass; `ldlt` then holds the
// factor of the scaled reduced matrix over `idx`. False (`message` says why) when nothing is
// determinable or a factorisation fails.
bool
rankTest(const SparseMatrix& N, const GaussMarkovProblem& problem, std::vector<bool>& estimated,
         Eigen::SimplicialLDLT<SparseMatrix>& ldlt, std::vector<int>& idx, std::string& message)
{
  for (;;) {
    idx = indicesOf(estimated);
    if (idx.empty()) {
      message = "the geometry determines none of the free parameters (singular normal matrix)";
      return false;
    }
    const SparseMatrix S = scaledReduced(N, idx, problem.scaling);
    // A shift far below the threshold keeps exactly dependent columns factorable (pivot ≈ shift).
    SparseMatrix shifted = S;
    const double shift = 1e-3 * problem.determinability_threshold * S.diagonal().cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < S.rows(); ++i)
      shifted.coeffRef(i, i) += shift;
    ldlt.compute(shifted);
    const int weak =
        ldlt.info() == Eigen::Success ? weakestPivot(ldlt, S, problem.determinability_threshold) : -2;
    if (weak == -2) {
      message = "sparse factorisation of the normal matrix failed";
      return false;
    }
    if (weak < 0) {
      ldlt.compute(S);
      if (ldlt.info() != Eigen::Success) {
        message = "sparse factorisation of the normal matrix failed";
        return false;
      }
      return true;
    }
    estimated[static_cast<std::size_t>(idx[static_cast<std::size_t>(weak)])] = false;
  }
}

// dx (eq. 10) and Qxx (eq. 14) of the estimated parameters `idx` from the factor of the scaled
// reduced matrix: N_r⁻¹ = D S⁻¹ D. False (the message says why) when they are not finite.
bool
solveReduced(const Eigen::SimplicialLDLT<SparseMatrix>& ldlt, const Eigen::VectorXd& b,
             const std::vector<int>& idx, const GaussMarkovProblem& problem, GaussMarkovSolution& sol)
{
  const auto k = static_cast<Eigen::Index>(idx.size());
  Eigen::VectorXd scale(k), br(k);
  for (Eigen::Index r = 0; r < k; ++r) {
    scale[r] = problem.scaling[idx[static_cast<std::size_t>(r)]];
    br[r] = b[idx[static_cast<std::size_t>(r)]];
  }
  const Eigen::VectorXd dxr = -(scale.asDiagonal() * ldlt.solve(scale.asDiagonal() * br)).eval();   // eq. 10
  const Eigen::MatrixXd Qr = scale.asDiagonal() * ldlt.solve(Eigen::MatrixXd(scale.asDiagonal()));  // eq. 14
  if (!dxr.allFinite() || !Qr.allFinite()) {
    sol.message = "solve produced non-finite values";
    return false;
  }
  for (Eigen::Index r = 0; r < k; ++r) {
    const int i = idx[static_cast<std::size_t>(r)];
    sol.dx[i] = dxr[r];
    for (Eigen::Index c = 0; c < k; ++c)
      sol.qxx(i, idx[static_cast<std::size_t>(c)]) = Qr(r, c);
  }
  return true;
}

GaussMarkovSolution
solveSparse(const BlockNormalEquations& ne, const GaussMarkovProblem& problem)
{
  const Eigen::Index u = ne.unknowns();
  GaussMarkovSolution sol;
  sol.dx = Eigen::VectorXd::Zero(u);
  sol.qxx = Eigen::MatrixXd::Zero(u, u);
  sol.fixed.assign(static_cast<std::size_t>(u), false);
  std::vector<bool> estimated(static_cast<std::size_t>(u), false);
  SparseMatrix N = ne.sparseMatrix();
  Eigen::VectorXd b = ne.rhs();
  addAprioriObservations(problem, N, b, sol.fixed, estimated);
  Eigen::SimplicialLDLT<SparseMatrix> ldlt;
  std::vector<int> idx;
  if (!rankTest(N, problem, estimated, ldlt, idx, sol.message) || !solveReduced(ldlt, b, idx, problem, sol))
    return sol;
  sol.determinable = estimated;
  sol.unknowns = static_cast<int>(idx.size());
  const SparseMatrix N0 = ne.sparseMatrix();
  detail::fillResidualStatistics(N0, ne.rhs(), ne.ltpl(), ne.observations(), sol.dx, idx, problem, sol);
  sol.ok = true;
  return sol;
}

}  // namespace

GaussMarkovSolution
solveGaussMarkov(const BlockNormalEquations& ne, const GaussMarkovProblem& problem, Eigen::Index dense_limit)
{
  const Eigen::Index u = ne.unknowns();
  if (problem.current.size() != u || problem.apriori_values.size() != u ||
      problem.apriori_weights.size() != u || problem.scaling.size() != u) {
    GaussMarkovSolution sol;
    sol.message = "normal equations and problem differ in size";
    return sol;
  }
  if (u <= dense_limit)
    return solveGaussMarkov(ne.denseMatrix(), ne.rhs(), ne.ltpl(), ne.observations(), problem);
  return solveSparse(ne, problem);
}

}  // namespace pcl_ls3d
