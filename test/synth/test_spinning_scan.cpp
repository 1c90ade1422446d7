// The spinning-LiDAR generator against its scene: every point lies on a scene surface within the
// range noise (distance functions of the solids, independent of the ray casting), the beam
// pattern is the scanner's, and the pair's truth maps source points onto the same surfaces.
#include <pcl_ls3d/synth/spinning_scan.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

using namespace pcl_ls3d::synth;

namespace {

double
distanceToBox(const Box& b, const Eigen::Vector3d& p)
{
  const Eigen::Vector3d outside = (b.lo - p).cwiseMax(p - b.hi).cwiseMax(0.0);
  if (outside.squaredNorm() > 0.0)
    return outside.norm();
  return (p - b.lo).cwiseMin(b.hi - p).minCoeff();  // inside: distance to the nearest face
}

double
distanceToCylinder(const Cylinder& c, const Eigen::Vector3d& p)
{
  const double radial = std::abs((p.head<2>() - c.base.head<2>()).norm() - c.radius);
  const double below = c.base.z() - p.z(), above = p.z() - (c.base.z() + c.height);
  return std::max({radial, below, above});
}

/// Distance from a world point to the nearest scene surface.
double
distanceToScene(const StreetScene& scene, const Eigen::Vector3d& p)
{
  const Eigen::Vector3d n = Eigen::Vector3d(-scene.slope.x(), -scene.slope.y(), 1.0).normalized();
  double d = std::abs((p.z() - scene.groundHeight(p.x(), p.y())) * n.z());
  for (const Box& b : scene.boxes)
    d = std::min(d, distanceToBox(b, p));
  for (const Cylinder& c : scene.cylinders)
    d = std::min(d, distanceToCylinder(c, p));
  for (const Sphere& s : scene.spheres)
    d = std::min(d, std::abs((p - s.centre).norm() - s.radius));
  return d;
}

/// Share of the cloud's points, mapped by `to_world`, within `tolerance` of a scene surface.
double
shareOnScene(const pcl::PointCloud<pcl::PointXYZ>& cloud, const StreetScene& scene,
             const Eigen::Isometry3d& to_world, double tolerance)
{
  std::size_t on = 0;
  for (const auto& p : cloud)
    on += distanceToScene(scene, to_world * p.getVector3fMap().cast<double>()) <= tolerance;
  return static_cast<double>(on) / static_cast<double>(cloud.size());
}

}  // namespace

TEST(SpinningScan, PointsLieOnTheSceneWithTheBeamPattern)
{
  const SpinningScanPair pair = makeSpinningScanPair();
  const SpinningScannerSettings s;
  ASSERT_GT(pair.target->size(), 40000u);
  ASSERT_LT(pair.target->size(), static_cast<std::size_t>(s.beams * s.azimuth_steps));
  // 5 σ of the range noise (float coordinates add < 1e-5 m).
  EXPECT_GT(shareOnScene(*pair.target, pair.scene, pair.target_pose, 5.0 * s.range_sigma), 0.999);
  std::set<int> elevations;
  for (const auto& p : *pair.target) {
    const double range = p.getVector3fMap().norm();
    EXPECT_GE(range, s.min_range - 5.0 * s.range_sigma);
    EXPECT_LE(range, s.max_range + 5.0 * s.range_sigma);
    elevations.insert(static_cast<int>(std::lround(std::asin(p.z / range) * 180.0 / M_PI * 2.0)));
  }
  // 32 beams 1.33° apart; the range noise blurs an elevation by < 0.1° beyond 12 m.
  EXPECT_GE(elevations.size(), 28u);
  EXPECT_LE(elevations.size(), 70u);
}

TEST(SpinningScan, TruthMapsTheSourceOntoTheTargetFrame)
{
  const SpinningScanPair pair = makeSpinningScanPair(1.5, 3.0, 2);
  const SpinningScannerSettings s;
  const Eigen::Isometry3d truth(pair.truth);
  // Source → target frame by the truth → world by the target's pose: on the scene.
  EXPECT_GT(shareOnScene(*pair.source, pair.scene, pair.target_pose * truth, 5.0 * s.range_sigma), 0.999);
  // A truth tilted by 2° (pitch) puts the ground beyond 3 m and the facades off the surfaces.
  const Eigen::Isometry3d off = truth * Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d::UnitY());
  EXPECT_LT(shareOnScene(*pair.source, pair.scene, pair.target_pose * off, 5.0 * s.range_sigma), 0.9);
  EXPECT_NEAR(pair.truth(0, 3), 1.5 * std::cos(1.5 * M_PI / 180.0), 1e-9);
  // The scans see the same street but are different samples of it (independent noise).
  EXPECT_NE(pair.source->size(), 0u);
  EXPECT_NE((*pair.source)[0].x, (*pair.target)[0].x);
}
