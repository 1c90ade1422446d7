#pragma once
/// \file masked_estimator.h
/// \brief An estimator composed with a set of held-out source points: their observations get
///        weight 0 while they lie beyond `cut` ŝ (ŝ the inner estimator's scale). After a
///        high-breakdown fit, the points beyond 2.5 ŝ of it are left out of the following
///        least-squares / M step (Rousseeuw & Leroy 1987, p. 202); a held-out point returns once
///        the fit reaches it, so a start slightly off does not keep good points out for good,
///        while a deformation stays out as long as it stands clear. The set follows the points
///        across iterations through the observation set (Observation::point).

#include <pcl_ls3d/estimators/robust_estimator_base.h>
#include <pcl_ls3d/estimators/robust_scale.h>

#include <cstdint>
#include <vector>

namespace pcl_ls3d {

class MaskedEstimator final : public RobustEstimator
{
public:
  /// \param[in] inner the estimator whose weights are kept otherwise
  /// \param[in] held_out per source point (the engine's point list): 1 = held out
  /// \param[in] cut held-out points count again within cut ŝ
  MaskedEstimator(RobustEstimator::ConstPtr inner, std::vector<std::uint8_t> held_out,
                  double cut = kReweightingCut)
      : inner_(std::move(inner)), held_out_(std::move(held_out)), cut_(cut)
  {}
  std::string
  name() const override
  {
    return inner_->name() + " holding out the start's outliers";
  }
  bool
  needsResidualSigmas() const override
  {
    return inner_->needsResidualSigmas();
  }
  void
  weigh(const WeightingInput& input, Eigen::Ref<Eigen::VectorXd> weights) const override;
  double
  scale(const WeightingInput& input) const override
  {
    return inner_->scale(input);
  }
  /// Without the observation set there are no points to mask: the inner estimator's weights.
  void
  computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v, double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const override
  {
    inner_->computeWeights(residuals, sigma_v, sigma0, weights);
  }

private:
  RobustEstimator::ConstPtr inner_;
  std::vector<std::uint8_t> held_out_;
  double cut_;
};

}  // namespace pcl_ls3d
