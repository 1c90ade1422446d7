/// \file adaptive_thresholds.cpp
/// \brief v_t, d_t, s_t and V_t of IMRG from the stats helpers.

#include <pcl_ls3d/segmentation/adaptive_thresholds.h>

#include <pcl_ls3d/stats/data_snooping.h>
#include <pcl_ls3d/stats/descriptive.h>
#include <pcl_ls3d/stats/kmeans_1d.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace segmentation {
namespace {

/// Backward elimination of large values, then the maximum of what remains.
double
snoopedMaximum(const std::vector<double>& values, double alpha)
{
  if (values.empty())
    return 0.0;
  stats::DataSnoopingSettings s;
  s.alpha = alpha;
  s.one_sided_upper = true;
  const stats::DataSnoopingResult r = stats::dataSnooping(values, s);
  return r.valid ? r.max_kept : 0.0;
}

}  // namespace

double
seedResidualThreshold(const std::vector<PointFeatures>& features)
{
  std::vector<double> linear;
  for (const auto& f : features)
    if (f.dimensionality == Dimensionality::Linear)
      linear.push_back(f.residual);
  return linear.empty() ? std::numeric_limits<double>::infinity() : stats::median(linear);
}

double
distanceThreshold(const std::vector<double>& nearest_distances, double alpha)
{
  return snoopedMaximum(nearest_distances, alpha);
}

double
similarityThreshold(const std::vector<double>& segment_residuals, int centres)
{
  const stats::KMeans1DResult km =
      stats::kMeans1D(segment_residuals, static_cast<std::size_t>(std::max(2, centres)));
  if (km.valid && std::isfinite(km.smallest_gap))
    return km.smallest_gap;
  return std::numeric_limits<double>::infinity();
}

double
volumeChangeThreshold(const std::vector<double>& volume_changes, double alpha)
{
  std::vector<double> roots;
  for (const double v : volume_changes)
    if (v >= 0.0 && std::isfinite(v))
      roots.push_back(std::cbrt(v));
  if (roots.empty())
    return 0.0;
  const double m = snoopedMaximum(roots, alpha);
  return m * m * m;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
