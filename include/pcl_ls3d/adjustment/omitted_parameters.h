#pragma once
/// \file omitted_parameters.h
/// \brief Is the model too small? A score (Lagrange-multiplier) test of the parameters an
///        adjustment held out (the scale of a rigid model), from their normal-equation columns
///        at the final pose: nothing is refitted.
///
/// At the solution of the restricted model the gradient of the estimated parameters E vanishes;
/// the held-out ones O keep g_O = A_Oᵀ P v. Freeing them would move them, in one Gauss–Newton
/// step from the solution, by θ = −K⁻¹ s with s = g_O − N_OE Q_EE g_E (the score with E
/// profiled out) and K = N_OO − N_OE Q_EE N_EO (their information left after E).
///
/// Which variance: s = Lᵀ g with Lᵀ = [−N_OE Q_EE | I], so Var(θ) = K⁻¹ Lᵀ Var(g) L K⁻¹, which is
/// also the (O, O) block of the freed model's sandwich Q_f M Q_f (Q_f = N_f⁻¹ has rows K⁻¹ Lᵀ
/// there). Taking Var(g) = σ0² N (independent observations) gives the textbook LM test, which
/// on surface matching fires on every real block: observations sharing target points are
/// correlated and the formal variance is several times too small (spatial_precision.h). The
/// test therefore takes Var(g) = M, the same spatial middle term (HAC cells, CR3 leverage
/// correction, a-priori terms) as the adjustment's own sandwich C = Q M Q, so θ's σ is the σ the
/// freed parameter would get from that sandwich, never below the formal σ0² K⁻¹ (as there).
/// M is estimated from the residuals after the freed one-step, v + A dx_f, with the freed Q_f:
/// from the restricted residuals a real scale would inflate its own variance (the misfit it
/// leaves is spatially coherent) and hide itself; under a right restricted model dx_f ≈ 0 and
/// both are the same. Under a right restricted model θ / σ ~ N(0, 1) as far as the sandwich σ
/// are honest (docs/MODEL_ADEQUACY.md).

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace pcl_ls3d {

/// \brief One held-out parameter, as it would be if freed.
struct OmittedParameter
{
  int index = -1;             ///< into the adjustment's parameter vector
  double estimate = 0.0;      ///< θ: the change it would take (one Gauss–Newton step)
  double sigma = 0.0;         ///< σ of θ from the sandwich's middle term, at least sigma_formal
  double sigma_formal = 0.0;  ///< σ0 √(K⁻¹)_ii
  double z = 0.0;             ///< θ / σ
};

/// \brief The test of all held-out parameters together and one by one.
struct OmittedParameterTest
{
  bool ok = false;                           ///< false: K singular or inputs inconsistent
  std::string message;                       ///< why not ok
  std::vector<OmittedParameter> parameters;  ///< in the order of `omitted`
  double statistic = 0.0;  ///< θᵀ C_θ⁻¹ θ: χ² with parameters.size() degrees of freedom under H0
};

/// The sandwich's middle term M (u × u) for residuals v + A·step (step over the whole parameter
/// vector) and the cofactor matrix q of the leverage correction; σ0² (N + P_e) when the
/// precision is formal.
using MiddleTermFn = std::function<Eigen::MatrixXd(const Eigen::VectorXd& step, const Eigen::MatrixXd& q)>;

/// \brief The score test. All matrices u × u over the whole parameter vector:
///  - `normal`: N = AᵀPA at the final pose; held-out parameters that the freed model would
///    observe softly (a soft datum) carry that a-priori weight on their diagonal;
///  - `gradient`: AᵀPv at the final pose, with the a-priori observations' part P_e(X − L_e)
///    added for estimated parameters;
///  - `qxx`: (N_EE + P_e)⁻¹ of the last solve, zero in the rows and columns of parameters that
///    were not estimated (held out, fixed, undeterminable): those are ignored;
///  - `middle`: the sandwich's middle term, called once with the freed one-step and Q_f;
///  - `omitted`: indices of the held-out parameters to test.
OmittedParameterTest
testOmittedParameters(const Eigen::MatrixXd& normal, const Eigen::VectorXd& gradient,
                      const Eigen::MatrixXd& qxx, const MiddleTermFn& middle, double sigma0,
                      const std::vector<int>& omitted);

}  // namespace pcl_ls3d
