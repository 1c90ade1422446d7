#include <pcl_ls3d/estimators/robust_estimator.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <iterator>
#include <utility>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace pcl_ls3d {

namespace {
// σ for residual i: σ_vi when given, else σ0.
inline double
sigmaOf(const Eigen::Ref<const Eigen::VectorXd>& sigma_v, Eigen::Index i, double sigma0)
{
  return sigma_v.size() > i && sigma_v[i] > 0.0 ? sigma_v[i] : sigma0;
}

std::string
named(const char* base, double k)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%s(%g)", base, k);
  return buf;
}
}  // namespace

void
LeastSquaresEstimator::computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                                      const Eigen::Ref<const Eigen::VectorXd>&, double,
                                      Eigen::Ref<Eigen::VectorXd> weights) const
{
  weights.setOnes();
}

std::string
ZuoEstimator::name() const
{
  return named("zuo-K", k_);
}

void
ZuoEstimator::computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                             const Eigen::Ref<const Eigen::VectorXd>&, double sigma0,
                             Eigen::Ref<Eigen::VectorXd> weights) const
{
  // eq. 15: p_i = 0 where |v_i| > K σ0, else 1; all ones while σ0 is unknown.
  const double limit = sigma0 > 0.0 ? k_ * sigma0 : std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < residuals.size(); ++i)
    weights[i] = std::abs(residuals[i]) > limit ? 0.0 : 1.0;
}

std::string
HuberEstimator::name() const
{
  return named("huber", k_);
}

void
HuberEstimator::computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                               const Eigen::Ref<const Eigen::VectorXd>& sigma_v, double sigma0,
                               Eigen::Ref<Eigen::VectorXd> weights) const
{
  for (Eigen::Index i = 0; i < residuals.size(); ++i) {
    const double s = sigmaOf(sigma_v, i, sigma0);
    const double u = s > 0.0 ? std::abs(residuals[i]) / s : 0.0;
    weights[i] = u <= k_ ? 1.0 : k_ / u;
  }
}

std::string
TukeyEstimator::name() const
{
  return named("tukey", c_);
}

void
TukeyEstimator::computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                               const Eigen::Ref<const Eigen::VectorXd>&, double sigma0,
                               Eigen::Ref<Eigen::VectorXd> weights) const
{
  // Robust scale: σ = 1.4826 · median |v| (residuals are centred on 0 by construction).
  std::vector<double> a(static_cast<std::size_t>(residuals.size()));
  for (Eigen::Index i = 0; i < residuals.size(); ++i)
    a[static_cast<std::size_t>(i)] = std::abs(residuals[i]);
  double sigma = 0.0;
  if (!a.empty()) {
    auto mid = a.begin() + static_cast<std::ptrdiff_t>(a.size() / 2);
    std::nth_element(a.begin(), mid, a.end());
    sigma = 1.4826 * *mid;
  }
  if (!(sigma > 0.0))  // more than half the residuals exactly 0: fall back to σ0
    sigma = sigma0;
  for (Eigen::Index i = 0; i < residuals.size(); ++i) {
    if (!(sigma > 0.0)) {  // no scale at all: plain least squares
      weights[i] = 1.0;
      continue;
    }
    const double u = residuals[i] / (c_ * sigma);
    weights[i] = std::abs(u) <= 1.0 ? (1.0 - u * u) * (1.0 - u * u) : 0.0;
  }
}

}  // namespace pcl_ls3d

namespace pcl_ls3d {

RobustEstimator::Ptr
makeRobustEstimator(RobustEstimatorType type, double constant)
{
  const bool given = std::isfinite(constant);
  switch (type) {
  case RobustEstimatorType::LEAST_SQUARES: return std::make_shared<LeastSquaresEstimator>();
  case RobustEstimatorType::ZUO: return std::make_shared<ZuoEstimator>(given ? constant : 6.0);
  case RobustEstimatorType::HUBER: return std::make_shared<HuberEstimator>(given ? constant : 1.345);
  case RobustEstimatorType::TUKEY: return std::make_shared<TukeyEstimator>(given ? constant : 4.685);
  }
  return nullptr;
}

RobustEstimator::Ptr
parseRobustEstimator(const std::string& text, std::string* why)
{
  auto fail = [why](const std::string& reason) -> RobustEstimator::Ptr {
    if (why)
      *why = reason;
    return nullptr;
  };
  std::string name = text.substr(0, text.find(':'));
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const std::pair<const char*, RobustEstimatorType> names[] = {
      {"ls", RobustEstimatorType::LEAST_SQUARES}, {"least-squares", RobustEstimatorType::LEAST_SQUARES},
      {"zuo", RobustEstimatorType::ZUO},          {"huber", RobustEstimatorType::HUBER},
      {"tukey", RobustEstimatorType::TUKEY}};
  const auto* found = std::find_if(std::begin(names), std::end(names),
                                   [&](const auto& entry) { return name == entry.first; });
  if (found == std::end(names))
    return fail("unknown estimator '" + name + "' (ls, zuo, huber, tukey)");
  double constant = std::numeric_limits<double>::quiet_NaN();
  const std::size_t colon = text.find(':');
  if (colon != std::string::npos) {
    const std::string number = text.substr(colon + 1);
    char* end = nullptr;
    constant = std::strtod(number.c_str(), &end);
    if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(constant) ||
        !(constant > 0.0))
      return fail("tuning constant of '" + name + "' must be a positive number, got '" + number + "'");
    if (found->second == RobustEstimatorType::LEAST_SQUARES)
      return fail("least squares has no tuning constant");
  }
  return makeRobustEstimator(found->second, constant);
}

}  // namespace pcl_ls3d
