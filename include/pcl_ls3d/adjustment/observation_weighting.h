#pragma once
/// \file observation_weighting.h
/// \brief Stage 4 of the engine: the weights p_i of one iteration's observations (Zuo et al.
///        2012, eq. 15 by default). One place decides the scale the estimator sees (σ0 of the
///        previous solve, or a robust start scale before the first), computes the residual
///        sigmas and redundancy numbers an estimator asks for, and clamps every weight to
///        [0, 1] (NaN counts as 0), so no later stage has to.

#include <pcl_ls3d/adjustment/observation_set.h>
#include <pcl_ls3d/common/parallel.h>
#include <pcl_ls3d/estimators/robust_estimator.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {

/// Robust stand-in for σ0 before the first solve: the MAD about zero, kMadToSigma · median |l|
/// (the residuals' centre is zero by construction, so it is not estimated); 0 when empty.
double
robustScale(const Eigen::VectorXd& l);

/// p in [0, 1]; NaN → 0.
inline double
clampWeight(double p)
{
  return std::min(1.0, std::max(0.0, p));
}

/// \brief Computes and holds the weights of the current iteration.
class ObservationWeighting
{
public:
  /// \param[in] row       row(j) → design row a_j at the current estimate
  /// \param[in] sigma0    σ0 of the previous solve (≤ 0 before the first)
  /// \param[in] qxx       Qxx of the previous solve (same size as a row), for r_i and σ_vi
  template <typename RowFn, typename Matrix>
  const Eigen::VectorXd&
  compute(const RobustEstimator& estimator, const ObservationSet& set, RowFn row, double sigma0,
          const Matrix& qxx, int iteration, double min_cut = 0.0)
  {
    const Eigen::Index m = static_cast<Eigen::Index>(set.size());
    l_ = set.distances();
    sigma_v_.resize(0);
    redundancy_.resize(0);
    if (estimator.needsResidualSigmas() && sigma0 > 0.0) {
      sigma_v_.resize(m);
      redundancy_.resize(m);
#pragma omp parallel for schedule(static) if (worthParallel(static_cast <std::size_t>(m)))
      for (Eigen::Index j = 0; j < m; ++j) {
        const auto a = row(static_cast<std::size_t>(j));
        redundancy_[j] = std::max(0.0, 1.0 - (a * qxx * a.transpose())(0, 0));
        sigma_v_[j] = sigma0 * std::sqrt(redundancy_[j]);
      }
    }
    const double scale = sigma0 > 0.0 ? sigma0 : robustScale(l_);
    weights_.resize(m);
    WeightingInput input(l_, sigma_v_, redundancy_, scale, &set, iteration);
    estimator.weigh(input, weights_);
    // Weigh again with the floor to learn whether it, not the estimator, set the cut.
    floor_bound_ = false;
    if (min_cut > 0.0) {
      unfloored_.swap(weights_);
      weights_.resize(m);
      input.min_cut = min_cut;
      estimator.weigh(input, weights_);
      floor_bound_ = weights_ != unfloored_;
    }
    for (Eigen::Index j = 0; j < m; ++j)
      weights_[j] = clampWeight(weights_[j]);
    return weights_;
  }

  /// True when the last compute()'s weights were set by its min_cut, not by the estimator.
  bool
  floorBound() const
  {
    return floor_bound_;
  }

  /// The weights of the last compute(), each in [0, 1].
  const Eigen::VectorXd&
  weights() const
  {
    return weights_;
  }

private:
  Eigen::VectorXd l_, sigma_v_, redundancy_, weights_, unfloored_;
  bool floor_bound_ = false;  // the last compute()'s weights were set by its min_cut
};

}  // namespace pcl_ls3d
