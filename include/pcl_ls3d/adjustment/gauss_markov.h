#pragma once
/// \file gauss_markov.h
/// \brief Stage 3 of the engine: one Gauss–Markoff solve with a-priori parameter observations
///        (Zuo et al. 2012, eqs. 9–11, 14) for any number of unknowns u (7 for a pair, 7 per
///        strip for a block): fixed parameters eliminated, a rank test for undeterminable ones.

#include <pcl_ls3d/adjustment/normal_equations.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl_ls3d {

/// \brief Inputs of one solve besides the normal equations (vectors of length u).
struct GaussMarkovProblem
{
  /// u unknowns: zero current values, zero a-priori values and weights, unit scaling.
  explicit GaussMarkovProblem(int unknowns = 7);

  Eigen::VectorXd current;          ///< X0, the current estimate
  Eigen::VectorXd apriori_values;   ///< L_e (values the a-priori observations state)
  Eigen::VectorXd apriori_weights;  ///< P_e: 0 free, +inf fixed, else soft
  /// Column scaling for the rank test, so all columns are comparable (e.g. 1 for t, the source
  /// radius for angles and scale: "displacement at the edge of the data").
  Eigen::VectorXd scaling;
  double determinability_threshold = 1e-7;  ///< relative eigenvalue limit
};

/// \brief Result of one solve; held (fixed or undeterminable) parameters get dx = 0 and zero
///        rows/columns in Qxx.
struct GaussMarkovSolution
{
  bool ok = false;
  std::string message;
  Eigen::VectorXd dx;              ///< X̂ − X0 = −(AᵀPA + P_e)⁻¹ (AᵀPL + P_e L_e), eq. 10
  Eigen::MatrixXd qxx;             ///< (AᵀPA + P_e)⁻¹ over the estimated parameters (eq. 14)
  std::vector<bool> fixed;         ///< infinite a-priori weight
  std::vector<bool> determinable;  ///< estimated (free and passed the rank test)
  int unknowns = 0;                ///< u: estimated parameters
  int soft_constraints = 0;        ///< a-priori observations with finite weight > 0 on estimated parameters
  double vtpv = 0.0;               ///< VᵀPV after the update (eq. 12)
  double vetpve = 0.0;             ///< V_eᵀP_eV_e after the update (eq. 13)
  long redundancy = 0;             ///< r = n + soft_constraints − u
  double sigma0 = 0.0;             ///< √((VᵀPV + V_eᵀP_eV_e) / r), eq. 11; 0 when r ≤ 0
};

/// Solves N dx = −b with a-priori observations: N = AᵀPA (u × u, symmetric), b = AᵀPL,
/// ltpl = LᵀPL, n observations with p > 0. Never throws.
GaussMarkovSolution
solveGaussMarkov(const Eigen::MatrixXd& N, const Eigen::VectorXd& b, double ltpl, std::size_t n,
                 const GaussMarkovProblem& problem);

/// The same for accumulated fixed-size normal equations.
template <int Dim>
GaussMarkovSolution
solveGaussMarkov(const NormalEquationsN<Dim>& ne, const GaussMarkovProblem& problem)
{
  return solveGaussMarkov(ne.N, ne.b, ne.ltpl, ne.n, problem);
}

}  // namespace pcl_ls3d
