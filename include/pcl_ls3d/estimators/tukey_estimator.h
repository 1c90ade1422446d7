#pragma once
/// \file tukey_estimator.h
/// \brief Tukey's biweight M-estimator, Li et al.'s "M" (2001, eqs. 6–8).

#include <pcl_ls3d/estimators/robust_estimator_base.h>
#include <pcl_ls3d/estimators/robust_scale.h>

namespace pcl_ls3d {

/// \brief ψ(u) = u (1 − u²/c²)² for |u| ≤ c, else 0 (eq. 6); IRLS weight w(u) = ψ(u)/u =
///        (1 − u²/c²)² (eq. 8), with u = v / σ̂. c = 4.685: 95 % efficiency at the normal.
///        σ̂ by default from eq. 7, 1.4826 med |v − med v| of the current residuals; ScaleRule
///        FIXED holds it at a given value (the M-step of an MM-estimator), SIGMA0 uses the
///        previous solve's σ̂0. A redescending ψ: observations beyond c σ̂ get weight 0.
class TukeyEstimator final : public RobustEstimator
{
public:
  explicit TukeyEstimator(double c = kTukey95, ScaleRule rule = ScaleRule::MAD, double fixed_scale = 0.0)
      : c_(c), rule_(rule), fixed_(fixed_scale)
  {}
  std::string
  name() const override;
  double
  scale(const WeightingInput& input) const override;
  void
  computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v, double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const override;
  double
  c() const
  {
    return c_;
  }

private:
  const double c_;
  const ScaleRule rule_;
  const double fixed_;
};

/// Tukey's weight (1 − (u/c)²)² for |u| ≤ c, else 0.
inline double
tukeyWeight(double u, double c)
{
  const double t = u / c;
  return t * t < 1.0 ? (1.0 - t * t) * (1.0 - t * t) : 0.0;
}

}  // namespace pcl_ls3d
