#include <pcl_ls3d/estimators/robust_scale.h>
#include <pcl_ls3d/stats/data_snooping.h>
#include <pcl_ls3d/stats/descriptive.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace pcl_ls3d {

namespace {
std::vector<double>
finiteValues(const Eigen::Ref<const Eigen::VectorXd>& v)
{
  std::vector<double> a;
  a.reserve(static_cast<std::size_t>(v.size()));
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (std::isfinite(v[i]))
      a.push_back(v[i]);
  return a;
}
}  // namespace

const char*
toString(ScaleRule rule)
{
  switch (rule) {
  case ScaleRule::SIGMA0:
    return "sigma0";
  case ScaleRule::MAD:
    return "mad";
  case ScaleRule::FIXED:
    return "fixed";
  }
  return "?";
}

double
madScale(const Eigen::Ref<const Eigen::VectorXd>& v)
{
  std::vector<double> a = finiteValues(v);
  if (a.size() < 2)
    return 0.0;
  const double med = stats::medianHigh(a);
  for (double& x : a)
    x = std::abs(x - med);
  return stats::kMadToSigma * stats::medianHigh(std::move(a));
}

double
tukeyRho(double u, double c)
{
  const double t = u / c;
  if (std::abs(t) >= 1.0)
    return 1.0;
  const double s = 1.0 - t * t;
  return 1.0 - s * s * s;
}

double
mScale(const Eigen::Ref<const Eigen::VectorXd>& v, double c, double b, double start)
{
  const std::vector<double> a = finiteValues(v);
  if (a.empty())
    return 0.0;
  double s = start > 0.0 ? start : madScale(v);
  if (!(s > 0.0)) {  // MAD 0: start from the RMS
    double ss = 0.0;
    for (double x : a)
      ss += x * x;
    s = std::sqrt(ss / static_cast<double>(a.size()));
  }
  if (!(s > 0.0))
    return 0.0;
  const double n = static_cast<double>(a.size());
  for (int it = 0; it < 100; ++it) {
    double sum = 0.0;
    for (double x : a)
      sum += tukeyRho(x / s, c);
    const double next = s * std::sqrt(sum / (n * b));
    if (!(next > 0.0))
      return 0.0;
    const bool done = std::abs(next - s) <= 1e-10 * s;
    s = next;
    if (done)
      break;
  }
  return s;
}

double
lmsScale(double median_squared, std::size_t n, int p)
{
  const double dof = static_cast<double>(n) - static_cast<double>(p);
  const double correction = dof > 0.0 ? 1.0 + 5.0 / dof : 1.0;
  return stats::kMadToSigma * correction * std::sqrt(std::max(0.0, median_squared));
}

double
lmsFinalScale(const Eigen::Ref<const Eigen::VectorXd>& v, double s0, int p)
{
  if (!(s0 > 0.0))
    return 0.0;
  const double limit = kReweightingCut * s0;
  double ss = 0.0;
  std::size_t inside = 0;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (std::abs(v[i]) <= limit) {
      ss += v[i] * v[i];
      ++inside;
    }
  const double dof = static_cast<double>(inside) - static_cast<double>(p);
  return dof > 0.0 ? std::sqrt(ss / dof) : 0.0;
}

double
ltsScale(double trimmed_mean_squared, double alpha)
{
  alpha = std::min(1.0, std::max(1e-6, alpha));
  if (alpha >= 1.0)
    return std::sqrt(std::max(0.0, trimmed_mean_squared));
  const double q = stats::normalCriticalValue(1.0 - alpha);  // P(|Z| ≤ q) = α
  const double phi = std::exp(-0.5 * q * q) / std::sqrt(2.0 * M_PI);
  const double factor = 1.0 - 2.0 * q * phi / alpha;
  return std::sqrt(std::max(0.0, trimmed_mean_squared) / factor);
}

double
reweightedScale(const Eigen::Ref<const Eigen::VectorXd>& v, double start, double c)
{
  if (!(start > 0.0) || !(c > 0.0))
    return 0.0;
  const double phi = std::exp(-0.5 * c * c) / std::sqrt(2.0 * M_PI);
  const double inside = std::erf(c / std::sqrt(2.0));  // 2Φ(c) − 1
  const double kappa = 1.0 - 2.0 * c * phi / inside;
  double s = start;
  for (int it = 0; it < 100; ++it) {
    const double limit = c * s;
    double ss = 0.0;
    std::size_t n = 0;
    for (Eigen::Index i = 0; i < v.size(); ++i)
      if (std::abs(v[i]) <= limit) {
        ss += v[i] * v[i];
        ++n;
      }
    if (n == 0)
      return 0.0;
    const double next = std::sqrt(ss / (static_cast<double>(n) * kappa));
    const bool done = std::abs(next - s) <= 1e-9 * s;
    s = next;
    if (done || !(s > 0.0))
      break;
  }
  return s;
}

double
scaleByRule(ScaleRule rule, const Eigen::Ref<const Eigen::VectorXd>& v, double sigma0, double fixed)
{
  switch (rule) {
  case ScaleRule::SIGMA0:
    return sigma0 > 0.0 ? sigma0 : madScale(v);
  case ScaleRule::MAD:
    return madScale(v);
  case ScaleRule::FIXED:
    return fixed;
  }
  return 0.0;
}

}  // namespace pcl_ls3d
