#pragma once
/// \file md_estimator.h
/// \brief Li et al.'s M-D estimator (2001, eq. 10): a GM-estimator, Tukey's ψ on Baarda's
///        normalised residual.

#include <pcl_ls3d/estimators/robust_estimator_base.h>
#include <pcl_ls3d/estimators/robust_scale.h>

namespace pcl_ls3d {

/// \brief u_i = v_i / σ_vi with σ_vi = σ̂ √r_i (Baarda's statistic: σ_vi = σ0 √(r_i/p_i)
///        with unit a-priori weight p_i), r_i = 1 − a_iᵀ Qxx a_i the redundancy number of the
///        previous solve, then Tukey's weight w(u) = (1 − u²/c²)² for |u| ≤ c (eq. 6), c = 4.685.
///        Observations of low redundancy (far from the centre, high leverage) are judged by their
///        own precision, so they cannot hide a large residual behind their leverage.
///        σ̂ = σ̂0 of the previous solve by default (Baarda's σ0; ScaleRule::MAD standardises
///        v_i / √r_i by their MAD instead). Note: σ̂0² = Σ w v² / (n − u) with Tukey's weights
///        settles about 17 % below σ for clean Gaussian residuals (E[w(Z) Z²] = 0.76 at c = 4.685,
///        iterated), so M-D cuts harder than Li's M (c·σ̂ ≈ 3.9 σ); deformed observations that
///        get weight 0 do not inflate it, unlike the MAD of all residuals (eq. 7). The first iteration has no redundancy numbers yet:
///        r_i = 1. r_i is floored at 1e-4 (an uncontrolled observation gets u large, w → 0).
class MdEstimator final : public RobustEstimator
{
public:
  explicit MdEstimator(double c = kTukey95, ScaleRule rule = ScaleRule::SIGMA0, double fixed_scale = 0.0)
      : c_(c), rule_(rule), fixed_(fixed_scale)
  {}
  std::string
  name() const override;
  bool
  needsResidualSigmas() const override
  {
    return true;
  }
  void
  weigh(const WeightingInput& input, Eigen::Ref<Eigen::VectorXd> weights) const override;
  double
  scale(const WeightingInput& input) const override;
  /// sigma_v = σ0 √r_i as the engine passes them (empty: r_i = 1).
  void
  computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v, double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const override;

  /// Baarda-normalised residuals v_i / √max(r_i, 1e-4) (r empty: v itself).
  static Eigen::VectorXd
  normalised(const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& r);

private:
  void
  weighNormalised(const Eigen::VectorXd& t, double sigma0, Eigen::Ref<Eigen::VectorXd> weights) const;

  const double c_;
  const ScaleRule rule_;
  const double fixed_;
};

}  // namespace pcl_ls3d
