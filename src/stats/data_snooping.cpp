#include <pcl_ls3d/stats/data_snooping.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace pcl_ls3d {
namespace stats {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Mean and sample σ (n − 1) of the values at `idx`.
void
meanSigma(const std::vector<double>& x, const std::vector<std::size_t>& idx, double& m, double& s)
{
  m = 0.0;
  for (std::size_t i : idx)
    m += x[i];
  m /= static_cast<double>(idx.size());
  double ss = 0.0;
  for (std::size_t i : idx)
    ss += (x[i] - m) * (x[i] - m);
  s = idx.size() > 1 ? std::sqrt(ss / static_cast<double>(idx.size() - 1)) : 0.0;
}
}  // namespace

double
normalCriticalValue(double alpha)
{
  if (!(alpha > 0.0 && alpha < 1.0))
    return kNaN;
  // P(|Z| > k) = erfc(k / √2) is monotone in k: bisection to double precision.
  double lo = 0.0, hi = 40.0;
  for (int i = 0; i < 200 && hi - lo > 1e-13; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > alpha ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

DataSnoopingResult
dataSnooping(const std::vector<double>& values, const DataSnoopingSettings& settings)
{
  DataSnoopingResult res;
  res.critical_value = settings.critical_value > 0.0 ? settings.critical_value
                                                     : normalCriticalValue(settings.alpha);
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < values.size(); ++i)
    (std::isfinite(values[i]) ? kept : res.rejected).push_back(i);
  if (kept.empty() || !std::isfinite(res.critical_value)) {
    res.mean = res.sigma = res.max_kept = res.max_w = kNaN;
    res.kept = kept;
    return res;
  }
  res.valid = true;
  const bool known_sigma = settings.sigma_apriori > 0.0;
  const std::size_t min_kept = std::max<std::size_t>(settings.min_kept, 1);

  while (true) {
    double m = 0.0, s = 0.0;
    meanSigma(values, kept, m, s);
    if (known_sigma)
      s = settings.sigma_apriori;
    res.mean = m;
    res.sigma = s;
    res.max_w = 0.0;
    if (s <= 0.0)
      break;  // all kept values equal: nothing is a gross error
    std::size_t worst = 0;
    for (std::size_t j = 0; j < kept.size(); ++j) {
      const double d = values[kept[j]] - m;
      if (settings.one_sided_upper && d <= 0.0)
        continue;
      const double w = std::abs(d) / s;
      if (w > res.max_w) {
        res.max_w = w;
        worst = j;
      }
    }
    if (res.max_w <= res.critical_value || kept.size() <= min_kept)
      break;
    res.rejected.push_back(kept[worst]);
    kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(worst));
    ++res.iterations;
  }
  std::sort(res.rejected.begin(), res.rejected.end());
  res.max_kept = values[kept.front()];
  for (std::size_t i : kept)
    res.max_kept = std::max(res.max_kept, values[i]);
  res.kept = std::move(kept);
  return res;
}

BaardaTestResult
baardaTest(const std::vector<double>& v, const std::vector<double>& r,
           const std::vector<double>& p, double sigma0, double critical_value,
           double min_redundancy)
{
  BaardaTestResult res;
  const std::size_t n = v.size();
  if (r.size() != n || (!p.empty() && p.size() != n) || !(sigma0 > 0.0))
    return res;
  res.w.assign(n, 0.0);
  res.tested.assign(n, false);
  long argmax = -1;
  for (std::size_t i = 0; i < n; ++i) {
    const double pi = p.empty() ? 1.0 : p[i];
    if (!(r[i] > min_redundancy) || !(pi > 0.0))
      continue;
    res.tested[i] = true;
    res.w[i] = v[i] / (sigma0 * std::sqrt(r[i] / pi));
    if (std::abs(res.w[i]) > res.max_abs_w) {
      res.max_abs_w = std::abs(res.w[i]);
      argmax = static_cast<long>(i);
    }
  }
  res.worst = res.max_abs_w > critical_value ? argmax : -1;
  return res;
}

}  // namespace stats
}  // namespace pcl_ls3d
