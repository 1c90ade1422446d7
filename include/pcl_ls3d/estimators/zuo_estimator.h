#pragma once
/// \file zuo_estimator.h
/// \brief Zuo et al. 2012, eq. 15: the 0/1 weight at K σ0 (the LS3D default).

#include <pcl_ls3d/estimators/robust_estimator_base.h>

namespace pcl_ls3d {

/// \brief w = 0 if |v| > K σ̂0, else 1, with σ̂0 of the previous solve (σ_vi is not used, as in
///        the paper). In the first iteration the engine passes the robust start scale
///        1.4826 · median |v| instead (observation_weighting.h); all ones when no scale is given.
///        K = 6 by default (the paper uses 6 or 7).
///
///        That first scale comes from the majority: where most points already agree with the
///        guess and only a few see its error (spinning-LiDAR street scans 1.2 m apart along the
///        street, where only poles, trunks and car fronts see it), K times it cut those few and
///        the fit converged 1.2 m off. The cut therefore never goes below the engine's annealed
///        floor WeightingInput::min_cut (AdjustmentSettings::guess_uncertainty, halved each
///        iteration); docs/BENCHMARKS.md, "Spinning-LiDAR street scans".
class ZuoEstimator final : public RobustEstimator
{
public:
  explicit ZuoEstimator(double k = 6.0) : k_(k)
  {}
  std::string
  name() const override;
  /// computeWeights() with the cut at max(K σ0, input.min_cut).
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
