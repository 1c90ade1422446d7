/// \file rule_growing.cpp
/// \brief Per-set region growing of (I)MRG (Wang et al. 2021 §2, seed condition §3.1).

#include <pcl_ls3d/segmentation/rule_growing.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pcl_ls3d {
namespace segmentation {
namespace {

/// Thresholds of one run, precomputed once.
struct Rules
{
  double cos_principal;
  double cos_normal;
  double growth_sq;
  double plane_tol;  ///< growth radius × sin N_t: how far off a tangent plane one step may go
  double volumetric_sq;
  bool seed_condition;
  double residual_threshold;
};

/// Does neighbour j join the segment growing through i (same set assumed)?
bool
joins(std::size_t i, std::size_t j, const std::vector<Eigen::Vector3f>& points,
      const std::vector<PointFeatures>& features, const std::vector<Eigen::Vector3f>& normals, const Rules& r)
{
  const double d2 = (points[i] - points[j]).squaredNorm();
  switch (features[i].dimensionality) {
  case Dimensionality::Linear:
    return d2 <= r.growth_sq && std::abs(features[i].principal.dot(features[j].principal)) >= r.cos_principal;
  case Dimensionality::Planar:
    // On i's tangent plane too (an addition to the paper): a parallel surface beside a roof
    // edge (a crown's or hedge's top, a roof step) is not the roof.
    return d2 <= r.growth_sq && std::abs(normals[i].dot(normals[j])) >= r.cos_normal &&
           std::abs(static_cast<double>(normals[i].dot(points[j] - points[i]))) <= r.plane_tol;
  case Dimensionality::Volumetric:
    return d2 <= r.volumetric_sq;
  default:
    return false;
  }
}

/// IMRG §3.1: may point i (not the seed) carry the growth on? A planar point only below the
/// residual threshold v_t. The same idea for lines (an addition): a linear point at a junction
/// is absorbed but does not grow, so a line stops where it meets a structure (a wire at its
/// tower's cross arm, a pole at the ground) instead of running on into the next span.
bool
propagates(std::size_t i, const std::vector<PointFeatures>& features, const std::vector<char>& junction,
           const Rules& r)
{
  if (!r.seed_condition)
    return true;
  if (features[i].dimensionality == Dimensionality::Linear)
    return !junction[i];
  if (features[i].dimensionality != Dimensionality::Planar)
    return true;
  return features[i].residual < r.residual_threshold;
}

/// Linear points with a neighbour within the growth radius that lies off their line by more
/// than a fifth of that radius: something other than the line itself is within reach. The
/// test is on positions, not on the neighbour's features, because at a crossing the features
/// of both lines mix (an arm point next to a wire takes the wire's direction). A sagging span
/// deviates from its chord by far less over one growth radius.
std::vector<char>
linearJunctions(const std::vector<Eigen::Vector3f>& points, const std::vector<PointFeatures>& features,
                const std::vector<int>& graph, std::size_t k, const Rules& r)
{
  std::vector<char> out(points.size(), 0);
  const double off_sq = 0.04 * r.growth_sq;  // (growth radius / 5)²
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (features[i].dimensionality != Dimensionality::Linear)
      continue;
    const Eigen::Vector3f& d = features[i].principal;
    for (std::size_t c = 0; c < k && !out[i]; ++c) {
      const int j = graph[i * k + c];
      if (j < 0 || features[static_cast<std::size_t>(j)].dimensionality == Dimensionality::Invalid)
        continue;
      const Eigen::Vector3f v = points[static_cast<std::size_t>(j)] - points[i];
      const double along = v.dot(d);
      out[i] = v.squaredNorm() <= r.growth_sq && v.squaredNorm() - along * along > off_sq;
    }
  }
  return out;
}

}  // namespace

std::vector<int>
growRegions(const std::vector<Eigen::Vector3f>& points, const std::vector<PointFeatures>& features,
            const std::vector<Eigen::Vector3f>& normals, const std::vector<int>& graph,
            const GrowingSettings& settings)
{
  const std::size_t n = points.size();
  std::vector<int> labels(n, -1);
  const std::size_t k = settings.graph_k > 0 ? static_cast<std::size_t>(settings.graph_k) : 0;
  if (n == 0 || features.size() != n || normals.size() != n || graph.size() != n * k)
    return labels;

  Rules r;
  r.cos_principal = std::cos(settings.principal_angle);
  r.cos_normal = std::cos(settings.normal_angle);
  r.growth_sq = settings.growth_radius * settings.growth_radius;
  r.plane_tol = settings.growth_radius * std::sin(settings.normal_angle);
  r.volumetric_sq = settings.volumetric_radius * settings.volumetric_radius;
  r.seed_condition = settings.use_seed_condition && std::isfinite(settings.residual_threshold);
  r.residual_threshold = settings.residual_threshold;

  const std::vector<char> junction = linearJunctions(points, features, graph, k, r);
  // Seeds in order of increasing residual: flat interiors first, boundaries last.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return features[a].residual < features[b].residual; });

  int next_label = 0;
  std::vector<std::size_t> queue;
  for (const std::size_t seed : order) {
    if (labels[seed] >= 0 || features[seed].dimensionality == Dimensionality::Invalid)
      continue;
    const Dimensionality set = features[seed].dimensionality;
    labels[seed] = next_label;
    queue.assign(1, seed);
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const std::size_t i = queue[q];
      if (i != seed && !propagates(i, features, junction, r))
        continue;  // absorbed boundary point: does not grow further
      for (std::size_t c = 0; c < k; ++c) {
        const int j = graph[i * k + c];
        if (j < 0 || labels[j] >= 0 || features[j].dimensionality != set)
          continue;
        if (!joins(i, static_cast<std::size_t>(j), points, features, normals, r))
          continue;
        labels[j] = next_label;
        queue.push_back(static_cast<std::size_t>(j));
      }
    }
    ++next_label;
  }
  return labels;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
