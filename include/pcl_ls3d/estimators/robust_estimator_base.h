#pragma once
/// \file robust_estimator_base.h
/// \brief The weight-function estimator interface of the adjustment, as small polymorphic
///        objects held by shared pointer (Ceres LossFunction / pcl::SampleConsensusModel style).
///        The concrete estimators have one header each; robust_estimator.h is the catalogue.
///
/// Contract for every estimator: given all residuals v_i of one iteration, their standard
/// deviations σ_vi (may be empty: then the scale is used for every observation) and the scale
/// (σ0 of the previous iteration, or a robust start scale in the first one), fill weights w_i in
/// [0, 1] with w = 1 for v = 0 and w(−v) = w(v). The whole vector is passed so that scale
/// estimators (MAD) and Baarda's test can be written as estimators too. The engine calls
/// weigh(), which also hands over the observation set itself (which source point each residual
/// belongs to, stable across iterations, and where its conjugate point lies) and, on request,
/// the redundancy numbers; the engine clamps the weights to [0, 1] afterwards
/// (adjustment/observation_weighting.h). IRLS (Li et al. 2001, eqs. 8–9) is the engine's own
/// Gauss–Markoff loop with these weights: there is no second adjustment engine.

#include <pcl_ls3d/adjustment/observation_set.h>

#include <Eigen/Core>

#include <memory>
#include <string>

namespace pcl_ls3d {

/// \brief Everything an estimator may look at in one iteration.
struct WeightingInput
{
  WeightingInput(const Eigen::VectorXd& residuals_, const Eigen::VectorXd& sigma_v_,
                 const Eigen::VectorXd& redundancy_, double scale_,
                 const ObservationSet* observations_ = nullptr, int iteration_ = 0)
      : residuals(residuals_), sigma_v(sigma_v_), redundancy(redundancy_), scale(scale_),
        observations(observations_), iteration(iteration_)
  {}

  const Eigen::VectorXd& residuals;  ///< v_i (the signed distances at the current estimate)
  /// σ_vi = σ0 √r_i from the previous solve when needsResidualSigmas(), else empty.
  const Eigen::VectorXd& sigma_v;
  /// r_i = 1 − a_iᵀ Qxx a_i (unit a-priori weight) when needsResidualSigmas(), else empty.
  const Eigen::VectorXd& redundancy;
  /// σ0 of the previous iteration; in the first, 1.4826 · median |v| (robust start scale).
  double scale;
  /// The observations behind the residuals (same order), or null when called without them.
  const ObservationSet* observations;
  int iteration;  ///< 1 for the first iteration
  /// The engine's annealed floor for estimators that cut (AdjustmentSettings::guess_uncertainty
  /// halved each iteration): |v| up to this is never cut. 0: none.
  double min_cut = 0.0;
};

/// \brief Abstract robust estimator: one main virtual, computeWeights().
class RobustEstimator
{
public:
  using Ptr = std::shared_ptr<RobustEstimator>;
  using ConstPtr = std::shared_ptr<const RobustEstimator>;

  virtual ~RobustEstimator() = default;

  /// Short name for reports.
  virtual std::string
  name() const = 0;

  /// True when the estimator uses σ_vi = σ0 √(r_i / p_i) (the engine then computes them from
  /// the previous iteration's Qxx; otherwise an empty vector is passed).
  virtual bool
  needsResidualSigmas() const
  {
    return false;
  }

  /// \brief The engine's entry point. The default hands the residuals to computeWeights();
  ///        estimators that follow observations across iterations or need their positions or
  ///        redundancy numbers override this.
  virtual void
  weigh(const WeightingInput& input, Eigen::Ref<Eigen::VectorXd> weights) const
  {
    computeWeights(input.residuals, input.sigma_v, input.scale, weights);
  }

  /// \brief σ̂, the scale this estimator standardises the given residuals with (u = v / σ̂),
  ///        for reports. The default is the engine's scale (σ0 of the previous solve).
  virtual double
  scale(const WeightingInput& input) const
  {
    return input.scale;
  }

  /// \param[in] residuals v_i of the current iteration
  /// \param[in] sigma_v σ_vi per residual, or an empty vector (use σ0)
  /// \param[in] sigma0 σ̂0 of the previous iteration (the engine passes 1.4826 · median |v| in
  ///            the first iteration); ≤ 0 when unknown
  /// \param[out] weights resized by the caller to residuals.size(); w_i in [0, 1]
  virtual void
  computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v, double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const = 0;
};

}  // namespace pcl_ls3d
