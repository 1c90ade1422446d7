#pragma once
// Steps shared by the dense and the block-sparse Gauss–Markoff solves (not installed).
#include <pcl_ls3d/adjustment/gauss_markov.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace pcl_ls3d {
namespace detail {

inline std::vector<int>
indicesOf(const std::vector<bool>& mask)
{
  std::vector<int> idx;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i])
      idx.push_back(static_cast<int>(i));
  return idx;
}

// VᵀPV (eq. 12 without storing V), V_eᵀP_eV_e (eq. 13), r and σ0 (eq. 11).
template <typename Matrix, typename Vector>
void
fillResidualStatistics(const Matrix& N, const Vector& b, double ltpl, std::size_t n, const Vector& dx,
                       const std::vector<int>& idx, const GaussMarkovProblem& problem,
                       GaussMarkovSolution& sol)
{
  sol.vtpv = std::max(0.0, ltpl + 2.0 * dx.dot(b) + dx.dot(N * dx));
  const Eigen::VectorXd& pe = problem.apriori_weights;
  for (int i : idx)
    if (pe[i] > 0.0) {
      const double ve = dx[i] + (problem.current[i] - problem.apriori_values[i]);
      sol.vetpve += pe[i] * ve * ve;
      ++sol.soft_constraints;
    }
  sol.redundancy = static_cast<long>(n) + sol.soft_constraints - sol.unknowns;
  if (sol.redundancy > 0)
    sol.sigma0 = std::sqrt((sol.vtpv + sol.vetpve) / static_cast<double>(sol.redundancy));
}

}  // namespace detail
}  // namespace pcl_ls3d
