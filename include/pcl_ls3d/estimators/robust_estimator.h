#pragma once
/// \file robust_estimator.h
/// \brief Weight-function estimators for the adjustment, as small polymorphic objects held by
///        shared pointer (Ceres LossFunction / pcl::SampleConsensusModel style).
///
/// Contract for every estimator: given all residuals v_i of one iteration, their standard
/// deviations σ_vi (may be empty: then σ0 is used for every observation) and σ0 of the previous
/// iteration (≤ 0 when not known yet, i.e. in the first iteration), fill weights w_i in [0, 1]
/// with w = 1 for v = 0 and w(−v) = w(v). The whole vector is passed so that scale estimators
/// (MAD) and Baarda's test can be written as estimators too.

#include <Eigen/Core>

#include <memory>
#include <string>

namespace pcl_ls3d {

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

}  // namespace pcl_ls3d
