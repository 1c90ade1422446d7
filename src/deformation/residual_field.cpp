#include <pcl_ls3d/common/voxel_index.h>
#include <pcl_ls3d/deformation/residual_field.h>

#include <pcl_ls3d/adjustment/pair_matcher.h>
#include <pcl_ls3d/adjustment/parameter_block.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace deformation {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double
median(std::vector<double> v)
{
  if (v.empty())
    return 0.0;
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

/// M3C2-style significance on the mean of the k nearest observed residuals (LOD95).
void
levelOfDetection(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& reg_variance,
                 const ResidualSettings& s, ResidualField& f)
{
  std::vector<Eigen::Vector3d> observed(points.size(), Eigen::Vector3d::Constant(kNaN));
  for (std::size_t i = 0; i < points.size(); ++i)
    if (std::isfinite(f.residual[i]))
      observed[i] = points[i];
  const VoxelIndex index(observed, 2.0 * std::max(cloudSpacing(observed).spacing, 1e-9));
  const std::vector<double> r = f.residual;
  const long n = static_cast<long>(points.size());
#pragma omp parallel
  {
    std::vector<int> nn;
#pragma omp for schedule(dynamic, 256)
    for (long i = 0; i < n; ++i) {
      const std::size_t u = static_cast<std::size_t>(i);
      if (!std::isfinite(r[u]))
        continue;
      index.nearestK(points[u], s.lod_neighbours, nn);
      double sum = 0.0, sq = 0.0;
      for (const int j : nn)
        sum += r[static_cast<std::size_t>(j)];
      const double k = static_cast<double>(nn.size());
      const double mean = sum / k;
      for (const int j : nn)
        sq += (r[static_cast<std::size_t>(j)] - mean) * (r[static_cast<std::size_t>(j)] - mean);
      const double spread2 = nn.size() > 1 ? sq / (k - 1.0) : f.sigma[u] * f.sigma[u];
      const double sigma = std::sqrt(spread2 / k) + std::sqrt(reg_variance[u]);
      f.residual[u] = mean;
      f.sigma[u] = sigma;
      f.significant[u] = std::abs(mean) > 1.96 * sigma;
    }
  }
}

}  // namespace

const char*
toString(DetectionRule rule)
{
  return rule == DetectionRule::LOD95 ? "lod95" : "sigma_k";
}

bool
ResidualSettings::isValid(std::string* why) const
{
  auto bad = [why](const char* reason) {
    if (why)
      *why = reason;
    return false;
  };
  if (!(k > 0.0) || !std::isfinite(k))
    return bad("k must be a positive number");
  if (lod_neighbours < 3 || lod_neighbours > 1000)
    return bad("lod_neighbours must be in [3, 1000]");
  if (!(max_distance > 0.0))
    return bad("max_distance must be > 0");
  return true;
}

ResidualField
computeResidualField(const std::vector<Eigen::Vector3d>& points, const TargetSurface& reference,
                     const ConjugateRule& rule, const AdjustmentReport& matching, double scale,
                     const ResidualSettings& s)
{
  ResidualField f;
  const std::size_t n = points.size();
  f.residual.assign(n, kNaN);
  f.sigma.assign(n, kNaN);
  f.significant.assign(n, 0);
  f.direction.assign(n, Eigen::Vector3d::Zero());
  f.scale = scale;
  // The matching's final pose: reduced frame o_s → o_t with its parameters.
  ParameterBlock block;
  block.input_origin = matching.local_origin_source;
  block.output_origin = matching.local_origin_target;
  block.values = matching.parameters;
  const ParameterBlock target = ParameterBlock::fixedIdentity(matching.local_origin_target);
  std::vector<Eigen::Vector3d> reduced;
  std::vector<std::size_t> index_of;
  for (std::size_t i = 0; i < n; ++i)
    if (points[i].allFinite()) {
      reduced.push_back(points[i] - block.input_origin);
      index_of.push_back(i);
    }
  PairMatcher matcher;
  matcher.reset(reduced, reference, rule, s.max_distance);
  const BlockLinearization pose(block);
  const ObservationSet& obs = matcher.match(pose, BlockLinearization(target), PairMatcher::Sampling());

  // r_i, σ²_surf,i and the propagated a C aᵀ of each point's first observation.
  std::vector<double> surface(n, 0.0), reg(n, 0.0), surfaces;
  for (const Observation& o : obs) {
    if (o.component != 0)
      continue;
    const std::size_t i = index_of[static_cast<std::size_t>(o.point)];
    const RowVector7d a = pose.designRow(o.direction, reduced[static_cast<std::size_t>(o.point)]);
    f.residual[i] = o.distance;
    f.direction[i] = o.direction;
    reg[i] = std::max(0.0, (a * matching.covariance * a.transpose())(0, 0));
    surface[i] = std::isfinite(o.surface_variance) ? std::max(0.0, o.surface_variance) : 0.0;
    surfaces.push_back(surface[i]);
  }
  const double med_surface = median(surfaces);
  f.median_surface_sigma = std::sqrt(med_surface);
  const double epoch_var = std::max(scale * scale - med_surface, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(f.residual[i]))
      continue;
    ++f.observed;
    f.sigma[i] = std::sqrt(epoch_var + surface[i] + reg[i]);
    f.significant[i] = std::abs(f.residual[i]) > s.k * f.sigma[i];
  }
  if (s.rule == DetectionRule::LOD95)
    levelOfDetection(points, reg, s, f);
  f.significant_count = static_cast<std::size_t>(std::count(f.significant.begin(), f.significant.end(), 1));
  return f;
}

}  // namespace deformation
}  // namespace pcl_ls3d
