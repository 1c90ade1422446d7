#include <pcl_ls3d/estimators/masked_estimator.h>

#include <cmath>

namespace pcl_ls3d {

void
MaskedEstimator::weigh(const WeightingInput& input, Eigen::Ref<Eigen::VectorXd> weights) const
{
  inner_->weigh(input, weights);
  if (!input.observations)
    return;
  const ObservationSet& obs = *input.observations;
  const double cut = cut_ * inner_->scale(input);
  for (Eigen::Index j = 0; j < weights.size() && static_cast<std::size_t>(j) < obs.size(); ++j) {
    const int p = obs[static_cast<std::size_t>(j)].point;
    if (p >= 0 && static_cast<std::size_t>(p) < held_out_.size() && held_out_[static_cast<std::size_t>(p)] &&
        std::abs(input.residuals[j]) > cut)
      weights[j] = 0.0;
  }
}

}  // namespace pcl_ls3d
