#include <pcl_ls3d/stats/data_snooping.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace pcl_ls3d {
namespace stats {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
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

namespace {

/// Prefix sums of the sorted sample about its median, accumulated from the small end, so that
/// removing large gross values cancels nothing.
struct PrefixSums
{
  double shift = 0.0;
  std::vector<long double> p1, p2;
};

PrefixSums
prefixSums(const std::vector<double>& values, const std::vector<std::size_t>& order)
{
  const std::size_t n = order.size();
  PrefixSums ps;
  ps.shift = values[order[n / 2]];
  ps.p1.assign(n + 1, 0.0L);
  ps.p2.assign(n + 1, 0.0L);
  for (std::size_t i = 0; i < n; ++i) {
    const long double d = static_cast<long double>(values[order[i]]) - ps.shift;
    ps.p1[i + 1] = ps.p1[i] + d;
    ps.p2[i + 1] = ps.p2[i] + d * d;
  }
  return ps;
}

/// Mean and σ (the a-priori one when given) of the kept range [lo, hi) of the sorted sample.
void
keptMoments(const PrefixSums& ps, std::size_t lo, std::size_t hi, const DataSnoopingSettings& settings,
            DataSnoopingResult& res)
{
  const std::size_t cnt = hi - lo;
  const long double s1 = ps.p1[hi] - ps.p1[lo], s2 = ps.p2[hi] - ps.p2[lo];
  const double m = ps.shift + static_cast<double>(s1 / cnt);
  double s = 0.0;
  if (cnt > 1) {
    const long double ss = std::max(0.0L, s2 - s1 * s1 / cnt);
    s = std::sqrt(static_cast<double>(ss / (cnt - 1)));
  }
  if (settings.sigma_apriori > 0.0)
    s = settings.sigma_apriori;
  res.mean = m;
  res.sigma = s;
}

/// One round of snooping on the kept range [lo, hi): the test value w of its extremes, and
/// the rejection of the larger one; false when it is no gross error or too few would remain.
bool
rejectExtreme(const std::vector<double>& values, const DataSnoopingSettings& settings, std::size_t min_kept,
              std::vector<std::size_t>& order, std::size_t& lo, std::size_t& hi, DataSnoopingResult& res)
{
  const double m = res.mean, s = res.sigma;
  // Candidates: the top value (if above the mean when one-sided) and the bottom value.
  const double d_hi = values[order[hi - 1]] - m, d_lo = values[order[lo]] - m;
  const double w_hi = (settings.one_sided_upper && d_hi <= 0.0) ? 0.0 : std::abs(d_hi) / s;
  const double w_lo = (settings.one_sided_upper && d_lo <= 0.0) ? 0.0 : std::abs(d_lo) / s;
  // Equal w: the one with the smaller input index, as a scan in input order would pick.
  std::size_t run = hi - 1;  // among equal top values, the smallest index
  while (run > lo && values[order[run - 1]] == values[order[hi - 1]])
    --run;
  const bool take_hi = w_hi > w_lo || (w_hi == w_lo && order[run] < order[lo]);
  res.max_w = std::max(w_hi, w_lo);
  if (res.max_w <= res.critical_value || hi - lo <= min_kept)
    return false;
  if (take_hi) {
    std::swap(order[run], order[hi - 1]);  // equal values: order stays sorted
    res.rejected.push_back(order[--hi]);
  } else {
    res.rejected.push_back(order[lo++]);
  }
  return true;
}

}  // namespace

DataSnoopingResult
dataSnooping(const std::vector<double>& values, const DataSnoopingSettings& settings)
{
  DataSnoopingResult res;
  res.critical_value =
      settings.critical_value > 0.0 ? settings.critical_value : normalCriticalValue(settings.alpha);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < values.size(); ++i)
    (std::isfinite(values[i]) ? order : res.rejected).push_back(i);
  if (order.empty() || !std::isfinite(res.critical_value)) {
    res.mean = res.sigma = res.max_kept = res.max_w = kNaN;
    res.kept = order;
    return res;
  }
  res.valid = true;
  const std::size_t min_kept = std::max<std::size_t>(settings.min_kept, 1);

  // The value farthest from the mean is always the smallest or the largest kept one, so the
  // kept set is a contiguous range [lo, hi) of the sorted sample: each round costs O(1) from
  // prefix sums (O(n log n) in all instead of O(n · rounds)).
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  const PrefixSums ps = prefixSums(values, order);
  std::size_t lo = 0, hi = order.size();
  while (true) {
    keptMoments(ps, lo, hi, settings, res);
    res.max_w = 0.0;
    if (res.sigma <= 0.0)
      break;  // all kept values equal: nothing is a gross error
    if (!rejectExtreme(values, settings, min_kept, order, lo, hi, res))
      break;
    ++res.iterations;
  }
  std::sort(res.rejected.begin(), res.rejected.end());
  res.kept.assign(order.begin() + static_cast<std::ptrdiff_t>(lo),
                  order.begin() + static_cast<std::ptrdiff_t>(hi));
  std::sort(res.kept.begin(), res.kept.end());
  res.max_kept = values[order[hi - 1]];
  return res;
}

BaardaTestResult
baardaTest(const std::vector<double>& v, const std::vector<double>& r, const std::vector<double>& p,
           double sigma0, double critical_value, double min_redundancy)
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
