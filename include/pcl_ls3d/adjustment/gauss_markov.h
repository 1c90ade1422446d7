#pragma once
/// \file gauss_markov.h
/// \brief One Gauss–Markoff solve with a-priori parameter observations (Zuo et al. 2012,
///        eqs. 9–11, 14): fixed parameters eliminated, a rank test for undeterminable ones.

#include <pcl_ls3d/adjustment/normal_equations.h>

#include <array>
#include <string>

namespace pcl_ls3d {

/// \brief Inputs of one solve besides the normal equations.
struct GaussMarkovProblem
{
  Vector7d current = Vector7d::Zero();          ///< X0, the current estimate
  Vector7d apriori_values = Vector7d::Zero();   ///< L_e (values the a-priori observations state)
  Vector7d apriori_weights = Vector7d::Zero();  ///< P_e: 0 free, +inf fixed, else soft
  /// Column scaling for the rank test, so all columns are comparable (e.g. 1 for t, the source
  /// radius for angles and scale: "displacement at the edge of the data").
  Vector7d scaling = Vector7d::Ones();
  double determinability_threshold = 1e-7;      ///< relative eigenvalue limit
};

/// \brief Result of one solve; held (fixed or undeterminable) parameters get dx = 0 and zero
///        rows/columns in Qxx.
struct GaussMarkovSolution
{
  bool ok = false;
  std::string message;
  Vector7d dx = Vector7d::Zero();       ///< X̂ − X0 = −(AᵀPA + P_e)⁻¹ (AᵀPL + P_e L_e), eq. 10
  Matrix7d qxx = Matrix7d::Zero();      ///< (AᵀPA + P_e)⁻¹ over the estimated parameters (eq. 14)
  std::array<bool, 7> fixed{};          ///< infinite a-priori weight
  std::array<bool, 7> determinable{};   ///< estimated (free and passed the rank test)
  int unknowns = 0;                     ///< u: estimated parameters
  int soft_constraints = 0;             ///< a-priori observations with finite weight > 0 on estimated parameters
  double vtpv = 0.0;                    ///< VᵀPV after the update (eq. 12)
  double vetpve = 0.0;                  ///< V_eᵀP_eV_e after the update (eq. 13)
  long redundancy = 0;                  ///< r = n + soft_constraints − u
  double sigma0 = 0.0;                  ///< √((VᵀPV + V_eᵀP_eV_e) / r), eq. 11; 0 when r ≤ 0
};

/// Solves the normal equations with a-priori observations. Never throws.
GaussMarkovSolution
solveGaussMarkov(const NormalEquations& ne, const GaussMarkovProblem& problem);

}  // namespace pcl_ls3d
