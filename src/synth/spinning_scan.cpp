#include <pcl_ls3d/synth/random.h>
#include <pcl_ls3d/synth/spinning_scan.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace synth {

namespace {

constexpr double kNoHit = std::numeric_limits<double>::infinity();

// Nearest t > 0 of a ray o + t d (|d| = 1) with each kind of solid; kNoHit without one.
double
hitGround(const StreetScene& scene, const Eigen::Vector3d& o, const Eigen::Vector3d& d)
{
  const Eigen::Vector3d n(-scene.slope.x(), -scene.slope.y(), 1.0);
  const double nd = n.dot(d);
  if (nd >= -1e-12)
    return kNoHit;
  const double t = -n.dot(o) / nd;
  return t > 0.0 ? t : kNoHit;
}

double
hitBox(const Box& b, const Eigen::Vector3d& o, const Eigen::Vector3d& d)
{
  double t0 = 0.0, t1 = kNoHit;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12) {
      if (o[a] < b.lo[a] || o[a] > b.hi[a])
        return kNoHit;
      continue;
    }
    double near = (b.lo[a] - o[a]) / d[a], far = (b.hi[a] - o[a]) / d[a];
    if (near > far)
      std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
    if (t0 > t1)
      return kNoHit;
  }
  return t0 > 0.0 ? t0 : kNoHit;  // a sensor inside a box sees nothing of it
}

double
hitCylinder(const Cylinder& c, const Eigen::Vector3d& o, const Eigen::Vector3d& d)
{
  const Eigen::Vector2d p = o.head<2>() - c.base.head<2>(), q = d.head<2>();
  const double a = q.squaredNorm(), b = p.dot(q), cc = p.squaredNorm() - c.radius * c.radius;
  const double disc = b * b - a * cc;
  if (a < 1e-12 || disc < 0.0)
    return kNoHit;
  const double t = (-b - std::sqrt(disc)) / a;
  const double z = o.z() + t * d.z();
  return t > 0.0 && z >= c.base.z() && z <= c.base.z() + c.height ? t : kNoHit;
}

double
hitSphere(const Sphere& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d)
{
  const Eigen::Vector3d p = o - s.centre;
  const double b = p.dot(d), disc = b * b - (p.squaredNorm() - s.radius * s.radius);
  if (disc < 0.0)
    return kNoHit;
  const double t = -b - std::sqrt(disc);
  return t > 0.0 ? t : kNoHit;
}

double
nearestHit(const StreetScene& scene, const Eigen::Vector3d& o, const Eigen::Vector3d& d)
{
  double t = hitGround(scene, o, d);
  for (const Box& b : scene.boxes)
    t = std::min(t, hitBox(b, o, d));
  for (const Cylinder& c : scene.cylinders)
    t = std::min(t, hitCylinder(c, o, d));
  for (const Sphere& s : scene.spheres)
    t = std::min(t, hitSphere(s, o, d));
  return t;
}

// Building blocks along one side of the street (side = ±1).
void
addBuildings(StreetScene& scene, double side, Random& rng)
{
  for (double x = -100.0; x < 100.0;) {
    const double length = rng.uniform(10.0, 30.0), setback = rng.uniform(9.0, 12.0);
    const double depth = rng.uniform(10.0, 15.0), height = rng.uniform(6.0, 20.0);
    const double y0 = side * setback, y1 = side * (setback + depth);
    const double base = scene.groundHeight(x + 0.5 * length, y0) - 1.0;
    scene.boxes.push_back({Eigen::Vector3d(x, std::min(y0, y1), base),
                           Eigen::Vector3d(x + length, std::max(y0, y1), base + 1.0 + height)});
    x += length + rng.uniform(2.0, 8.0);
  }
}

// Parked cars, poles and trees along one side.
void
addStreetFurniture(StreetScene& scene, double side, Random& rng)
{
  for (double x = -95.0; x < 95.0; x += rng.uniform(6.0, 12.0)) {
    if (rng.uniform() < 0.4)
      continue;
    const double y = side * 5.0, ground = scene.groundHeight(x, y);
    scene.boxes.push_back(
        {Eigen::Vector3d(x - 2.25, y - 0.9, ground - 0.2), Eigen::Vector3d(x + 2.25, y + 0.9, ground + 1.5)});
  }
  for (double x = -90.0; x < 90.0; x += 20.0) {
    const double y = side * 7.5;
    scene.cylinders.push_back({Eigen::Vector3d(x, y, scene.groundHeight(x, y) - 0.5), 0.12, 7.5});
  }
  for (double x = -82.0; x < 90.0; x += rng.uniform(12.0, 18.0)) {
    const double y = side * 8.0, ground = scene.groundHeight(x, y), r = rng.uniform(2.0, 3.0);
    scene.cylinders.push_back({Eigen::Vector3d(x, y, ground - 0.5), 0.2, 3.5 + 0.5 * r});
    scene.spheres.push_back({Eigen::Vector3d(x, y, ground + 3.0 + 0.8 * r), r});
  }
}

}  // namespace

StreetScene
makeStreetScene(std::uint32_t seed)
{
  StreetScene scene;
  Random rng(seed);
  for (double side : {-1.0, 1.0}) {
    addBuildings(scene, side, rng);
    addStreetFurniture(scene, side, rng);
  }
  return scene;
}

pcl::PointCloud<pcl::PointXYZ>
scanStreet(const StreetScene& scene, const Eigen::Isometry3d& sensor_pose,
           const SpinningScannerSettings& settings)
{
  pcl::PointCloud<pcl::PointXYZ> cloud;
  Random rng(settings.seed);
  const Eigen::Vector3d origin = sensor_pose.translation();
  const Eigen::Matrix3d R = sensor_pose.linear();
  const double deg = M_PI / 180.0;
  for (int a = 0; a < settings.azimuth_steps; ++a) {
    const double azimuth = 2.0 * M_PI * a / settings.azimuth_steps;
    for (int b = 0; b < settings.beams; ++b) {
      const double f = settings.beams > 1 ? static_cast<double>(b) / (settings.beams - 1) : 0.5;
      const double elevation =
          deg * (settings.elevation_min_deg + f * (settings.elevation_max_deg - settings.elevation_min_deg));
      const Eigen::Vector3d local(std::cos(elevation) * std::cos(azimuth),
                                  std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
      const double t = nearestHit(scene, origin, R * local);
      if (!(t >= settings.min_range && t <= settings.max_range))
        continue;
      const Eigen::Vector3f p = ((t + rng.normal(0.0, settings.range_sigma)) * local).cast<float>();
      cloud.push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    }
  }
  return cloud;
}

SpinningScanPair
makeSpinningScanPair(double forward, double yaw_deg, std::uint32_t seed,
                     const SpinningScannerSettings& settings)
{
  SpinningScanPair pair;
  pair.scene = makeStreetScene(seed);
  const StreetScene& scene = pair.scene;
  Eigen::Isometry3d& target_pose = pair.target_pose;
  target_pose.translation() = Eigen::Vector3d(0.0, 0.0, scene.groundHeight(0.0, 0.0) + 1.8);
  const double yaw = yaw_deg * M_PI / 180.0;
  const Eigen::Vector3d at(forward * std::cos(0.5 * yaw), forward * std::sin(0.5 * yaw), 0.0);
  Eigen::Isometry3d& source_pose = pair.source_pose;
  source_pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  source_pose.translation() = at + Eigen::Vector3d(0.0, 0.0, scene.groundHeight(at.x(), at.y()) + 1.8);

  SpinningScannerSettings s = settings;
  s.seed = settings.seed * 2 + 1;
  pair.target.reset(new pcl::PointCloud<pcl::PointXYZ>(scanStreet(scene, target_pose, s)));
  s.seed = settings.seed * 2 + 2;
  pair.source.reset(new pcl::PointCloud<pcl::PointXYZ>(scanStreet(scene, source_pose, s)));
  pair.truth = (target_pose.inverse() * source_pose).matrix();
  return pair;
}

}  // namespace synth
}  // namespace pcl_ls3d
