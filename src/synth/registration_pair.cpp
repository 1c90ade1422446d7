#include "sampling.h"

#include <pcl_ls3d/synth/registration_pair.h>

#include <pcl/console/print.h>

#include <cmath>

namespace pcl_ls3d {
namespace synth {

SimilarityTransform
defaultPairTruth()
{
  Vector7d p;
  p << 0.5, -0.3, 0.2, 2e-3, -1.5e-3, 3e-3, 1.0 + 2e-4;
  return SimilarityTransform(p);
}

bool
RegistrationPairSettings::isValid(std::string* why) const
{
  auto fail = [why](const char* msg) {
    if (why)
      *why = msg;
    return false;
  };
  if (!(size_x > 0.0 && size_y > 0.0))
    return fail("size_x and size_y must be positive");
  if (!(source_density > 0.0 && target_density > 0.0))
    return fail("densities must be positive");
  if (!(overlap > 0.0 && overlap <= 1.0))
    return fail("overlap must be in (0, 1]");
  if (!(noise_sigma >= 0.0))
    return fail("noise_sigma must be >= 0");
  if (!(relief >= 0.0 && wavelength > 0.0))
    return fail("relief must be >= 0 and wavelength > 0");
  if (!(truth.m > 0.0) || !truth.vector().allFinite() || !origin.allFinite())
    return fail("truth must be finite with m > 0, origin finite");
  const double n = size_x * size_y * (source_density + target_density);
  if (n > 2e9)
    return fail("too many points (more than 2e9)");
  if (std::lround(size_x * size_y * source_density) < 1 || std::lround(size_x * size_y * target_density) < 1)
    return fail("density × area gives no points");
  return true;
}

Eigen::Matrix4d
RegistrationPair::globalTruthMatrix() const
{
  return localToGlobal(truth.matrix(), origin, origin);
}

namespace {

/// Uniform samples of `surface` in `box`, noisy, then mapped by (A, b): p' = A p + b.
void
samplePair(const SurfaceModel& surface, const Eigen::AlignedBox2d& box, std::size_t n, double sigma,
           const Eigen::Matrix4d& map, std::uint32_t seed, std::uint32_t stream, std::uint16_t source_id,
           pcl::PointCloud<PointLiDAR>& cloud)
{
  cloud.resize(n);
  cloud.width = static_cast<std::uint32_t>(n);
  cloud.height = 1;
  cloud.is_dense = true;
  const Eigen::Matrix3d A = map.topLeftCorner<3, 3>();
  const Eigen::Vector3d b = map.topRightCorner<3, 1>();
  detail::forEachBlocked(n, seed, stream, [&](std::size_t i, Random& rng) {
    const double x = rng.uniform(box.min().x(), box.max().x());
    const double y = rng.uniform(box.min().y(), box.max().y());
    int building = -1;
    const double z = surface.height(x, y, &building);
    const Eigen::Vector3d p = A * (Eigen::Vector3d(x, y, z) + rng.normal3(sigma)) + b;
    PointLiDAR& q = cloud[i];
    q = detail::makePoint(p);
    q.classification = building >= 0 ? 6 : 2;
    q.intensity = static_cast<float>((building >= 0 ? 120.0 : 50.0) + rng.uniform(-10.0, 10.0));
    q.point_source_id = source_id;
    q.gps_time = 1000.0 * source_id + 1e-5 * static_cast<double>(i);
  });
}

}  // namespace

RegistrationPair
makeRegistrationPair(const RegistrationPairSettings& s)
{
  RegistrationPair pair;
  pair.source.reset(new pcl::PointCloud<PointLiDAR>);
  pair.target.reset(new pcl::PointCloud<PointLiDAR>);
  pair.truth = s.truth;
  pair.origin = s.origin;
  std::string why;
  if (!s.isValid(&why)) {
    PCL_ERROR("[pcl_ls3d::synth::makeRegistrationPair] invalid settings: %s\n", why.c_str());
    return pair;
  }
  const Eigen::Vector2d half(0.5 * s.size_x, 0.5 * s.size_y);
  pair.source_footprint = Eigen::AlignedBox2d(-half, half);
  const Eigen::Vector2d shift((1.0 - s.overlap) * s.size_x, 0.0);
  pair.target_footprint = Eigen::AlignedBox2d(-half + shift, half + shift);

  Terrain terrain(s.seed, s.relief, s.wavelength);
  std::vector<Building> buildings;
  if (s.buildings) {
    Eigen::AlignedBox2d all = pair.source_footprint;
    all.extend(pair.target_footprint);
    buildings = placeBuildings(terrain, all, s.building_settings, s.seed);
  }
  auto surface = std::make_shared<SurfaceModel>(terrain, BuildingSet(std::move(buildings)));
  pair.surface = surface;

  const double area = s.size_x * s.size_y;
  const auto ns = static_cast<std::size_t>(std::lround(area * s.source_density));
  const auto nt = static_cast<std::size_t>(std::lround(area * s.target_density));
  samplePair(*surface, pair.source_footprint, ns, s.noise_sigma, s.truth.matrix().inverse(), s.seed, 1u, 1,
             *pair.source);
  samplePair(*surface, pair.target_footprint, nt, s.noise_sigma, Eigen::Matrix4d::Identity(), s.seed, 2u, 2,
             *pair.target);
  return pair;
}

}  // namespace synth
}  // namespace pcl_ls3d
