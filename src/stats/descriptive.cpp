#include <pcl_ls3d/stats/descriptive.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace stats {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Type-7 quantile of an already sorted, non-empty sample.
double
sortedQuantile(const std::vector<double>& sorted, double p)
{
  if (std::isnan(p))
    return kNaN;
  p = std::min(1.0, std::max(0.0, p));
  const double h = static_cast<double>(sorted.size() - 1) * p;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}
}  // namespace

double
median(std::vector<double> values)
{
  if (values.empty())
    return kNaN;
  const std::size_t n = values.size();
  const std::size_t mid = n / 2;
  // nth_element is O(n); the lower middle of an even count is the max of the lower half.
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  const double upper = values[mid];
  if (n % 2 == 1)
    return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + mid);
  return 0.5 * (lower + upper);
}

double
medianHigh(std::vector<double> values)
{
  if (values.empty())
    return kNaN;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

double
mad(const std::vector<double>& values, bool scaled)
{
  if (values.empty())
    return kNaN;
  const double med = median(values);
  std::vector<double> dev(values.size());
  std::transform(values.begin(), values.end(), dev.begin(), [med](double x) { return std::abs(x - med); });
  const double m = median(std::move(dev));
  return scaled ? kMadToSigma * m : m;
}

double
quantile(std::vector<double> values, double p)
{
  if (values.empty())
    return kNaN;
  std::sort(values.begin(), values.end());
  return sortedQuantile(values, p);
}

std::vector<double>
quantiles(std::vector<double> values, const std::vector<double>& probs)
{
  std::vector<double> out(probs.size(), kNaN);
  if (values.empty())
    return out;
  std::sort(values.begin(), values.end());
  for (std::size_t i = 0; i < probs.size(); ++i)
    out[i] = sortedQuantile(values, probs[i]);
  return out;
}

double
mean(const std::vector<double>& values)
{
  if (values.empty())
    return kNaN;
  double sum = 0.0;
  for (double x : values)
    sum += x;
  return sum / static_cast<double>(values.size());
}

double
standardDeviation(const std::vector<double>& values)
{
  if (values.size() < 2)
    return kNaN;
  const double m = mean(values);
  double ss = 0.0;
  for (double x : values)
    ss += (x - m) * (x - m);
  return std::sqrt(ss / static_cast<double>(values.size() - 1));
}

}  // namespace stats
}  // namespace pcl_ls3d
