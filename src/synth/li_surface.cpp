#include "sampling.h"

#include <pcl_ls3d/synth/li_surface.h>
#include <pcl_ls3d/synth/terrain.h>

#include <pcl/console/print.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace pcl_ls3d {
namespace synth {

namespace {
const std::array<const char*, 9> kNames{"upper_left", "upper",      "upper_right", "left",       "middle",
                                        "right",      "lower_left", "lower",       "lower_right"};
}  // namespace

const char*
toString(DeformationPosition p)
{
  return kNames[static_cast<int>(p)];
}

bool
parseDeformationPosition(const std::string& name, DeformationPosition& p)
{
  for (int i = 0; i < 9; ++i)
    if (name == kNames[i]) {
      p = static_cast<DeformationPosition>(i);
      return true;
    }
  return false;
}

SimilarityTransform
defaultLiTruth()
{
  const double a = 5.0 * M_PI / 180.0;  // Li et al. 2001, Table 4: 5°, 5°, 5°, 500, 500, 500
  Vector7d p;
  p << 500.0, 500.0, 500.0, a, a, a, 1.0;
  return SimilarityTransform(p);
}

bool
LiSurfaceSettings::isValid(std::string* why) const
{
  auto fail = [why](const char* msg) {
    if (why)
      *why = msg;
    return false;
  };
  if (grid_size < 2 || grid_size > 20000)
    return fail("grid_size must be in [2, 20000]");
  if (!(spacing > 0.0 && relief >= 0.0 && wavelength > 0.0))
    return fail("spacing and wavelength must be positive, relief >= 0");
  if (!(noise_sigma >= 0.0))
    return fail("noise_sigma must be >= 0");
  if (!(deformation_percent >= 0.0 && deformation_percent <= 100.0))
    return fail("deformation_percent must be in [0, 100]");
  if (!std::isfinite(deformation_c))
    return fail("deformation_c must be finite");
  if (!(truth.m > 0.0) || !truth.vector().allFinite())
    return fail("truth must be finite with m > 0");
  return true;
}

/// Deformed nodes: the k nearest to the anchor (Chebyshev, then Euclidean, then index).
static std::vector<int>
gatheredNodes(int n, DeformationPosition position, std::size_t k)
{
  const int p = static_cast<int>(position);
  const double ax = 0.5 * (n - 1) * (p % 3);      // left, centre, right column
  const double ay = 0.5 * (n - 1) * (2 - p / 3);  // upper = last row (largest y)
  std::vector<int> order(static_cast<std::size_t>(n) * n);
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](int i) {
    const double dx = std::abs(i % n - ax), dy = std::abs(i / n - ay);
    return std::make_pair(std::max(dx, dy), dx * dx + dy * dy);
  };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  order.resize(k);
  std::sort(order.begin(), order.end());
  return order;
}

namespace {

/// The square grid's node coordinates, centred on the origin.
struct NodeGrid
{
  int n;
  double spacing, half;

  double
  x(std::size_t i) const
  {
    return -half + spacing * static_cast<double>(i % n);
  }
  double
  y(std::size_t i) const
  {
    return -half + spacing * static_cast<double>(i / n);
  }
};

/// Heights of the nodes rescaled to exactly `relief` peak-to-peak, centred on 0.
std::vector<double>
nodeHeights(const LiSurfaceSettings& s, const NodeGrid& grid, std::size_t total)
{
  const Terrain terrain(s.seed, 1.0, s.wavelength);
  std::vector<double> height(total);
  for (std::size_t i = 0; i < total; ++i)
    height[i] = terrain.height(grid.x(i), grid.y(i));
  const auto mm = std::minmax_element(height.begin(), height.end());
  const double lo = *mm.first, range = *mm.second - *mm.first;
  for (double& h : height)
    h = range > 0.0 ? s.relief * ((h - lo) / range - 0.5) : 0.0;
  return height;
}

/// The deformed nodes (deformation_percent of them, gathered at the position).
void
markDeformed(const LiSurfaceSettings& s, std::size_t total, LiSurface& out)
{
  const auto k = static_cast<std::size_t>(std::lround(s.deformation_percent / 100.0 * total));
  out.deformed_indices = gatheredNodes(s.grid_size, s.position, k);
  out.deformed.assign(total, 0);
  for (int i : out.deformed_indices)
    out.deformed[i] = 1;
  out.percent = 100.0 * static_cast<double>(k) / static_cast<double>(total);
}

/// The reference and the mate (noise, deformation, then the inverse of the truth) per node.
void
samplePoints(const LiSurfaceSettings& s, const NodeGrid& grid, std::size_t total, LiSurface& out)
{
  Random rng(s.seed, 0x11u, 0u);
  out.deformation.assign(total, 0.0);
  out.mate_noise.resize(total);
  const double sigma = s.noise_sigma;
  const Eigen::Matrix4d inverse = s.truth.matrix().inverse();
  out.reference->resize(total);
  out.mate->resize(total);
  for (std::size_t i = 0; i < total; ++i) {
    const double x = grid.x(i), y = grid.y(i);
    const double ref_noise = s.noise_on_reference ? rng.normal(0.0, sigma) : 0.0;
    out.mate_noise[i] = rng.normal(0.0, sigma);
    if (out.deformed[i])
      out.deformation[i] = rng.normal(s.deformation_c * sigma, sigma);
    PointLiDAR& r = (*out.reference)[i];
    r = detail::makePoint({x, y, out.height[i] + ref_noise});
    r.classification = 2;
    r.point_source_id = 1;
    const Eigen::Vector4d m(x, y, out.height[i] + out.mate_noise[i] + out.deformation[i], 1.0);
    PointLiDAR& q = (*out.mate)[i];
    q = detail::makePoint((inverse * m).head<3>());
    q.classification = 2;
    q.point_source_id = 2;
  }
}

}  // namespace

LiSurface
makeLiSurface(const LiSurfaceSettings& s)
{
  LiSurface out;
  out.reference.reset(new pcl::PointCloud<PointLiDAR>);
  out.mate.reset(new pcl::PointCloud<PointLiDAR>);
  out.truth = s.truth;
  std::string why;
  if (!s.isValid(&why)) {
    PCL_ERROR("[pcl_ls3d::synth::makeLiSurface] invalid settings: %s\n", why.c_str());
    return out;
  }
  const int n = s.grid_size;
  const std::size_t total = static_cast<std::size_t>(n) * n;
  const NodeGrid grid{n, s.spacing, 0.5 * (n - 1) * s.spacing};
  out.height = nodeHeights(s, grid, total);
  markDeformed(s, total, out);
  samplePoints(s, grid, total, out);
  for (auto* c : {out.reference.get(), out.mate.get()}) {
    c->width = static_cast<std::uint32_t>(total);
    c->height = 1;
    c->is_dense = true;
  }
  return out;
}

}  // namespace synth
}  // namespace pcl_ls3d
