#pragma once
/// \file robust_estimator.h
/// \brief Weight-function estimators for the adjustment, as small polymorphic objects held by
///        shared pointer (Ceres LossFunction / pcl::SampleConsensusModel style).
///
/// Contract for every estimator: given all residuals v_i of one iteration, their standard
/// deviations σ_vi (may be empty: then the scale is used for every observation) and the scale
/// (σ0 of the previous iteration, or a robust start scale in the first one), fill weights w_i in
/// [0, 1] with w = 1 for v = 0 and w(−v) = w(v). The whole vector is passed so that scale
/// estimators (MAD) and Baarda's test can be written as estimators too. The engine calls
/// weigh(), which also hands over the observation set itself (which source point each residual
/// belongs to, stable across iterations, and where its conjugate point lies) and, on request,
/// the redundancy numbers; the engine clamps the weights to [0, 1] afterwards
/// (adjustment/observation_weighting.h).

#include <pcl_ls3d/adjustment/observation_set.h>

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <string>

namespace pcl_ls3d {

/// \brief Everything an estimator may look at in one iteration.
struct WeightingInput
{
  WeightingInput(const Eigen::VectorXd& residuals_, const Eigen::VectorXd& sigma_v_,
                 const Eigen::VectorXd& redundancy_, double scale_,
                 const ObservationSet* observations_ = nullptr, int iteration_ = 0)
  : residuals(residuals_)
  , sigma_v(sigma_v_)
  , redundancy(redundancy_)
  , scale(scale_)
  , observations(observations_)
  , iteration(iteration_)
  {}

  const Eigen::VectorXd& residuals;   ///< v_i (the signed distances at the current estimate)
  /// σ_vi = σ0 √r_i from the previous solve when needsResidualSigmas(), else empty.
  const Eigen::VectorXd& sigma_v;
  /// r_i = 1 − a_iᵀ Qxx a_i (unit a-priori weight) when needsResidualSigmas(), else empty.
  const Eigen::VectorXd& redundancy;
  /// σ0 of the previous iteration; in the first, 1.4826 · median |v| (robust start scale).
  double scale;
  /// The observations behind the residuals (same order), or null when called without them.
  const ObservationSet* observations;
  int iteration;                      ///< 1 for the first iteration
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

  /// \param[in] residuals v_i of the current iteration
  /// \param[in] sigma_v σ_vi per residual, or an empty vector (use σ0)
  /// \param[in] sigma0 σ̂0 of the previous iteration (the engine passes 1.4826 · median |v| in
  ///            the first iteration); ≤ 0 when unknown
  /// \param[out] weights resized by the caller to residuals.size(); w_i in [0, 1]
  virtual void
  computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v,
                 double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const = 0;
};

/// \brief Plain least squares: w = 1.
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
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v,
                 double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const override;
};

/// \brief Zuo et al. 2012, eq. 15: w = 0 if |v| > K σ0, else 1 (σ_vi is not used, as in the
///        paper). All ones while σ0 is unknown (first iteration). K = 6 by default (the paper uses 6 or 7).
class ZuoEstimator final : public RobustEstimator
{
public:
  explicit ZuoEstimator(double k = 6.0) : k_(k) {}
  std::string
  name() const override;
  void
  computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v,
                 double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const override;
  double
  k() const
  {
    return k_;
  }

private:
  const double k_;
};

/// \brief Huber: w = 1 for |v/σ| ≤ k, else k / |v/σ|. w(0) = 1. k = 1.345 by default.
class HuberEstimator final : public RobustEstimator
{
public:
  explicit HuberEstimator(double k = 1.345) : k_(k) {}
  std::string
  name() const override;
  void
  computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v,
                 double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const override;

private:
  const double k_;
};

/// \brief Tukey biweight: w = (1 − (u/c)²)² for |u| ≤ c, else 0, with u = v/σ and σ from the
///        median absolute deviation (1.4826 MAD) of the residuals. c = 4.685 by default.
class TukeyEstimator final : public RobustEstimator
{
public:
  explicit TukeyEstimator(double c = 4.685) : c_(c) {}
  std::string
  name() const override;
  void
  computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v,
                 double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const override;

private:
  const double c_;
};

/// The estimators shipped with the library.
enum class RobustEstimatorType {
  LEAST_SQUARES,  ///< w = 1
  ZUO,            ///< Zuo et al. 2012, eq. 15: 0/1 weight at K σ0 (default K = 6)
  HUBER,          ///< Huber, k = 1.345 (95 % efficiency)
  TUKEY           ///< Tukey biweight on 1.4826 MAD, c = 4.685 (95 % efficiency)
};

/// Creates one of the shipped estimators; a finite `constant` replaces its default tuning
/// constant (K, k or c, in σ units).
RobustEstimator::Ptr
makeRobustEstimator(RobustEstimatorType type, double constant = std::numeric_limits<double>::quiet_NaN());

/// Parses "ls", "zuo", "huber", "tukey" (case-insensitive), optionally with a tuning constant
/// after a colon ("zuo:7", "huber:1.5"). Returns null and says why when the text is not one.
RobustEstimator::Ptr
parseRobustEstimator(const std::string& text, std::string* why = nullptr);

}  // namespace pcl_ls3d
