#include <pcl_ls3d/stats/kmeans_1d.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace stats {

namespace {
/// Index of the nearest centre in an ascending list (ties go to the lower centre).
int
nearestCentre(const std::vector<double>& centres, double x)
{
  const auto it = std::lower_bound(centres.begin(), centres.end(), x);
  if (it == centres.begin())
    return 0;
  if (it == centres.end())
    return static_cast<int>(centres.size()) - 1;
  const auto hi = static_cast<int>(it - centres.begin());
  return (x - *(it - 1) <= *it - x) ? hi - 1 : hi;
}

/// Seeds at the (c + ½)/k quantiles of a sorted sample of more than k distinct values; a seed
/// that repeats the previous one moves to the next distinct value above it.
std::vector<double>
quantileSeeds(const std::vector<double>& sorted, std::size_t k)
{
  std::vector<double> seeds;
  const std::size_t n = sorted.size();
  for (std::size_t c = 0; c < k; ++c) {
    const auto idx = static_cast<std::size_t>((static_cast<double>(c) + 0.5) / static_cast<double>(k) *
                                              static_cast<double>(n));
    double s = sorted[std::min(idx, n - 1)];
    if (!seeds.empty() && s <= seeds.back()) {
      const auto it = std::upper_bound(sorted.begin(), sorted.end(), seeds.back());
      if (it == sorted.end())
        break;
      s = *it;
    }
    seeds.push_back(s);
  }
  return seeds;
}
}  // namespace

KMeans1DResult
kMeans1D(const std::vector<double>& values, std::size_t k, std::size_t max_iterations)
{
  KMeans1DResult res;
  res.assignments.assign(values.size(), -1);
  res.smallest_gap = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> sorted;
  for (double x : values)
    if (std::isfinite(x))
      sorted.push_back(x);
  if (sorted.empty() || k == 0)
    return res;
  res.valid = true;
  std::sort(sorted.begin(), sorted.end());
  std::vector<double> distinct = sorted;
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());

  std::vector<double>& centres = res.centres;
  centres = distinct.size() <= k ? distinct : quantileSeeds(sorted, k);
  const bool exact = distinct.size() <= k;

  std::vector<int> assign(values.size(), -1);
  for (std::size_t it = 0; it < (exact ? 1 : max_iterations); ++it) {
    bool changed = false;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (!std::isfinite(values[i]))
        continue;
      const int c = nearestCentre(centres, values[i]);
      changed |= (c != assign[i]);
      assign[i] = c;
    }
    res.iterations = it + 1;
    if (!changed && it > 0) {
      res.converged = true;
      break;
    }
    // Update step: means; an empty cluster takes the value farthest from its centre.
    std::vector<double> sum(centres.size(), 0.0);
    std::vector<std::size_t> cnt(centres.size(), 0);
    for (std::size_t i = 0; i < values.size(); ++i)
      if (assign[i] >= 0) {
        sum[static_cast<std::size_t>(assign[i])] += values[i];
        ++cnt[static_cast<std::size_t>(assign[i])];
      }
    for (std::size_t c = 0; c < centres.size(); ++c) {
      if (cnt[c] > 0) {
        centres[c] = sum[c] / static_cast<double>(cnt[c]);
        continue;
      }
      double far = -1.0;
      for (std::size_t i = 0; i < values.size(); ++i)
        if (assign[i] >= 0) {
          const double d = std::abs(values[i] - centres[static_cast<std::size_t>(assign[i])]);
          if (d > far) {
            far = d;
            centres[c] = values[i];
          }
        }
    }
    std::sort(centres.begin(), centres.end());
  }
  if (exact)
    res.converged = true;

  // Final assignment against the final (sorted) centres, sizes and within-cluster SS.
  res.sizes.assign(centres.size(), 0);
  res.within_ss = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]))
      continue;
    const int c = nearestCentre(centres, values[i]);
    res.assignments[i] = c;
    ++res.sizes[static_cast<std::size_t>(c)];
    const double d = values[i] - centres[static_cast<std::size_t>(c)];
    res.within_ss += d * d;
  }
  for (std::size_t c = 1; c < centres.size(); ++c) {
    const double gap = centres[c] - centres[c - 1];
    if (std::isnan(res.smallest_gap) || gap < res.smallest_gap)
      res.smallest_gap = gap;
  }
  return res;
}

}  // namespace stats
}  // namespace pcl_ls3d
