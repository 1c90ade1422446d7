#pragma once
/// \file zuo_estimator.h
/// \brief Zuo et al. 2012, eq. 15: the 0/1 weight at K σ0 (the LS3D default).

#include <pcl_ls3d/estimators/robust_estimator_base.h>

namespace pcl_ls3d {

/// \brief w = 0 if |v| > K σ̂0, else 1, with σ̂0 of the previous solve (σ_vi is not used, as in
///        the paper). All ones while σ0 is unknown (first iteration). K = 6 by default (the
///        paper uses 6 or 7).
class ZuoEstimator final : public RobustEstimator
{
public:
  explicit ZuoEstimator(double k = 6.0) : k_(k) {}
  std::string
  name() const override;
  /// All ones in the first iteration (no σ0 yet; see the class comment).
  void
  weigh(const WeightingInput& input, Eigen::Ref<Eigen::VectorXd> weights) const override;
  void
  computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v, double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const override;
  double
  k() const
  {
    return k_;
  }

private:
  const double k_;
};

}  // namespace pcl_ls3d
