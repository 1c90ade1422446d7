#pragma once
/// \file huber_estimator.h
/// \brief Huber's M-estimator (Huber 1981): ρ quadratic inside k, linear outside.

#include <pcl_ls3d/estimators/robust_estimator_base.h>
#include <pcl_ls3d/estimators/robust_scale.h>

namespace pcl_ls3d {

/// \brief w(u) = 1 for |u| ≤ k, else k / |u|, with u = v / σ̂ (σ̂ = σ_vi when the engine passes
///        residual sigmas, else the scale rule's σ̂). w(0) = 1. k = 1.345: 95 % efficiency at
///        the normal; breakdown 0 in regression (monotone ψ), but bounded influence of a single
///        large residual. σ̂ = 1.4826 MAD by default (recomputed every iteration).
class HuberEstimator final : public RobustEstimator
{
public:
  explicit HuberEstimator(double k = kHuber95, ScaleRule rule = ScaleRule::MAD, double fixed_scale = 0.0)
      : k_(k), rule_(rule), fixed_(fixed_scale)
  {}
  std::string
  name() const override;
  double
  scale(const WeightingInput& input) const override;
  void
  computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v, double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const override;

private:
  const double k_;
  const ScaleRule rule_;
  const double fixed_;
};

}  // namespace pcl_ls3d
