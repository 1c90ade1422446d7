// Weights of the shipped weight-function estimators (one header each in estimators/).
#include <pcl_ls3d/estimators/robust_estimator.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace pcl_ls3d {

namespace {
std::string
named(const char* base, double k, ScaleRule rule, ScaleRule default_rule)
{
  char buf[64];
  if (rule == default_rule)
    std::snprintf(buf, sizeof(buf), "%s(%g)", base, k);
  else
    std::snprintf(buf, sizeof(buf), "%s(%g,%s)", base, k, toString(rule));
  return buf;
}

// σ for residual i: σ_vi when given, else s.
inline double
sigmaOf(const Eigen::Ref<const Eigen::VectorXd>& sigma_v, Eigen::Index i, double s)
{
  return sigma_v.size() > i && sigma_v[i] > 0.0 ? sigma_v[i] : s;
}

// σ̂ by the rule, falling back to σ0 when the rule gives none (e.g. MAD of one value).
double
scaleOrSigma0(ScaleRule rule, const Eigen::Ref<const Eigen::VectorXd>& v, double sigma0, double fixed)
{
  const double s = scaleByRule(rule, v, sigma0, fixed);
  return s > 0.0 ? s : sigma0;
}

// Zuo's 0/1 weight: 0 where |v_i| > limit, else 1.
void
zeroBeyond(const Eigen::Ref<const Eigen::VectorXd>& residuals, double limit,
           Eigen::Ref<Eigen::VectorXd> weights)
{
  for (Eigen::Index i = 0; i < residuals.size(); ++i)
    weights[i] = std::abs(residuals[i]) > limit ? 0.0 : 1.0;
}
}  // namespace

// ---- least squares -------------------------------------------------------------------
void
LeastSquaresEstimator::computeWeights(const Eigen::Ref<const Eigen::VectorXd>&,
                                      const Eigen::Ref<const Eigen::VectorXd>&, double,
                                      Eigen::Ref<Eigen::VectorXd> weights) const
{
  weights.setOnes();
}

// ---- Zuo eq. 15 ------------------------------------------------------------------------
std::string
ZuoEstimator::name() const
{
  return named("zuo-K", k_, ScaleRule::SIGMA0, ScaleRule::SIGMA0);
}

void
ZuoEstimator::computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                             const Eigen::Ref<const Eigen::VectorXd>&, double sigma0,
                             Eigen::Ref<Eigen::VectorXd> weights) const
{
  // eq. 15: p_i = 0 where |v_i| > K σ0, else 1; all ones while σ0 is unknown.
  zeroBeyond(residuals, sigma0 > 0.0 ? k_ * sigma0 : std::numeric_limits<double>::infinity(), weights);
}

void
ZuoEstimator::weigh(const WeightingInput& in, Eigen::Ref<Eigen::VectorXd> weights) const
{
  zeroBeyond(in.residuals,
             in.scale > 0.0 ? std::max(k_ * in.scale, in.min_cut) : std::numeric_limits<double>::infinity(),
             weights);
}

// ---- Huber -----------------------------------------------------------------------------
std::string
HuberEstimator::name() const
{
  return named("huber", k_, rule_, ScaleRule::MAD);
}

double
HuberEstimator::scale(const WeightingInput& in) const
{
  return scaleOrSigma0(rule_, in.residuals, in.scale, fixed_);
}

void
HuberEstimator::computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                               const Eigen::Ref<const Eigen::VectorXd>& sigma_v, double sigma0,
                               Eigen::Ref<Eigen::VectorXd> weights) const
{
  const double s = scaleOrSigma0(rule_, residuals, sigma0, fixed_);
  for (Eigen::Index i = 0; i < residuals.size(); ++i) {
    const double si = sigmaOf(sigma_v, i, s);
    const double u = si > 0.0 ? std::abs(residuals[i]) / si : 0.0;
    weights[i] = u <= k_ ? 1.0 : k_ / u;
  }
}

// ---- Tukey (Li's M) ------------------------------------------------------------------------
std::string
TukeyEstimator::name() const
{
  return named("tukey", c_, rule_, ScaleRule::MAD);
}

double
TukeyEstimator::scale(const WeightingInput& in) const
{
  return scaleOrSigma0(rule_, in.residuals, in.scale, fixed_);
}

void
TukeyEstimator::computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                               const Eigen::Ref<const Eigen::VectorXd>&, double sigma0,
                               Eigen::Ref<Eigen::VectorXd> weights) const
{
  const double s = scaleOrSigma0(rule_, residuals, sigma0, fixed_);
  for (Eigen::Index i = 0; i < residuals.size(); ++i)
    weights[i] = s > 0.0 ? tukeyWeight(residuals[i] / s, c_) : 1.0;  // no scale: least squares
}

// ---- M-D / GM (Li eq. 10) ---------------------------------------------------------------------
std::string
MdEstimator::name() const
{
  return named("m-d", c_, rule_, ScaleRule::SIGMA0);
}

Eigen::VectorXd
MdEstimator::normalised(const Eigen::Ref<const Eigen::VectorXd>& v,
                        const Eigen::Ref<const Eigen::VectorXd>& r)
{
  Eigen::VectorXd t = v;
  if (r.size() == v.size())
    for (Eigen::Index i = 0; i < v.size(); ++i)
      t[i] = v[i] / std::sqrt(std::max(r[i], 1e-4));
  return t;
}

void
MdEstimator::weighNormalised(const Eigen::VectorXd& t, double sigma0,
                             Eigen::Ref<Eigen::VectorXd> weights) const
{
  const double s = scaleOrSigma0(rule_, t, sigma0, fixed_);
  for (Eigen::Index i = 0; i < t.size(); ++i)
    weights[i] = s > 0.0 ? tukeyWeight(t[i] / s, c_) : 1.0;
}

void
MdEstimator::weigh(const WeightingInput& in, Eigen::Ref<Eigen::VectorXd> weights) const
{
  weighNormalised(normalised(in.residuals, in.redundancy), in.scale, weights);
}

double
MdEstimator::scale(const WeightingInput& in) const
{
  return scaleOrSigma0(rule_, normalised(in.residuals, in.redundancy), in.scale, fixed_);
}

void
MdEstimator::computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                            const Eigen::Ref<const Eigen::VectorXd>& sigma_v, double sigma0,
                            Eigen::Ref<Eigen::VectorXd> weights) const
{
  Eigen::VectorXd r;
  if (sigma_v.size() == residuals.size() && sigma0 > 0.0)
    r = (sigma_v / sigma0).array().square().matrix();  // σ_vi = σ0 √r_i
  weighNormalised(normalised(residuals, r), sigma0, weights);
}

}  // namespace pcl_ls3d
