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

/// The finite values, ascending.
std::vector<double>
finiteSorted(const std::vector<double>& values)
{
  std::vector<double> sorted;
  for (double x : values)
    if (std::isfinite(x))
      sorted.push_back(x);
  std::sort(sorted.begin(), sorted.end());
  return sorted;
}

/// Assignment step: each finite value to its nearest centre; true when any assignment changed.
bool
assignToNearest(const std::vector<double>& values, const std::vector<double>& centres,
                std::vector<int>& assign)
{
  bool changed = false;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]))
      continue;
    const int c = nearestCentre(centres, values[i]);
    changed |= (c != assign[i]);
    assign[i] = c;
  }
  return changed;
}

/// The value farthest from its assigned centre, or `fallback` when nothing is assigned.
double
farthestValue(const std::vector<double>& values, const std::vector<int>& assign,
              const std::vector<double>& centres, double fallback)
{
  double far = -1.0, value = fallback;
  for (std::size_t i = 0; i < values.size(); ++i)
    if (assign[i] >= 0) {
      const double d = std::abs(values[i] - centres[static_cast<std::size_t>(assign[i])]);
      if (d > far) {
        far = d;
        value = values[i];
      }
    }
  return value;
}

/// Update step: means; an empty cluster takes the value farthest from its centre. Centres stay
/// ascending.
void
updateCentres(const std::vector<double>& values, const std::vector<int>& assign, std::vector<double>& centres)
{
  std::vector<double> sum(centres.size(), 0.0);
  std::vector<std::size_t> cnt(centres.size(), 0);
  for (std::size_t i = 0; i < values.size(); ++i)
    if (assign[i] >= 0) {
      sum[static_cast<std::size_t>(assign[i])] += values[i];
      ++cnt[static_cast<std::size_t>(assign[i])];
    }
  for (std::size_t c = 0; c < centres.size(); ++c)
    centres[c] = cnt[c] > 0 ? sum[c] / static_cast<double>(cnt[c])
                            : farthestValue(values, assign, centres, centres[c]);
  std::sort(centres.begin(), centres.end());
}

/// Final assignment against the final (sorted) centres, sizes and within-cluster SS.
void
finalAssignment(const std::vector<double>& values, KMeans1DResult& res)
{
  const std::vector<double>& centres = res.centres;
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
}

/// The smallest difference of neighbouring ascending centres (NaN for fewer than two).
double
smallestGap(const std::vector<double>& centres)
{
  double smallest = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t c = 1; c < centres.size(); ++c) {
    const double gap = centres[c] - centres[c - 1];
    if (std::isnan(smallest) || gap < smallest)
      smallest = gap;
  }
  return smallest;
}
}  // namespace

KMeans1DResult
kMeans1D(const std::vector<double>& values, std::size_t k, std::size_t max_iterations)
{
  KMeans1DResult res;
  res.assignments.assign(values.size(), -1);
  res.smallest_gap = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> sorted = finiteSorted(values);
  if (sorted.empty() || k == 0)
    return res;
  res.valid = true;
  std::vector<double> distinct = sorted;
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());

  std::vector<double>& centres = res.centres;
  centres = distinct.size() <= k ? distinct : quantileSeeds(sorted, k);
  const bool exact = distinct.size() <= k;

  std::vector<int> assign(values.size(), -1);
  for (std::size_t it = 0; it < (exact ? 1 : max_iterations); ++it) {
    const bool changed = assignToNearest(values, centres, assign);
    res.iterations = it + 1;
    if (!changed && it > 0) {
      res.converged = true;
      break;
    }
    updateCentres(values, assign, centres);
  }
  if (exact)
    res.converged = true;
  finalAssignment(values, res);
  res.smallest_gap = smallestGap(centres);
  return res;
}

}  // namespace stats
}  // namespace pcl_ls3d
