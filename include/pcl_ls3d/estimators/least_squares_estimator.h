#pragma once
/// \file least_squares_estimator.h
/// \brief Plain least squares: w(u) = 1 (ρ(u) = u²; breakdown point 0).

#include <pcl_ls3d/estimators/robust_estimator_base.h>

namespace pcl_ls3d {

/// \brief w = 1 for every residual.
class LeastSquaresEstimator final : public RobustEstimator
{
public:
  std::string
  name() const override
  {
    return "least-squares";
  }
  void
  computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v, double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const override;
};

}  // namespace pcl_ls3d
