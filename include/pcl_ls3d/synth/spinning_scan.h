#pragma once
/// \file spinning_scan.h
/// \brief A street scanned by a spinning multi-beam LiDAR (Velodyne HDL-32E-like), by ray casting:
///        the sparse, ring-patterned scans of mobile mapping and LiDAR odometry, with a known
///        relative pose between two scans.
///
/// The street runs along x: a ground plane with a gentle slope, building blocks (boxes) on both
/// sides with gaps, cars (boxes), poles and tree trunks (vertical cylinders) and crowns
/// (spheres). Each beam is cast from the sensor, the nearest hit within the range limits is a
/// point, its range disturbed by N(0, range_sigma). Points are in the SENSOR frame, as a real
/// scanner writes them; a ray that hits nothing (sky) gives no point.

#include <pcl_ls3d/point_types.h>

#include <pcl/point_cloud.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace synth {

/// \brief Beam pattern and noise of the scanner (defaults: HDL-32E at 10 Hz).
struct SpinningScannerSettings
{
  int beams = 32;  ///< lasers, elevations evenly spread over the field of view
  double elevation_min_deg = -30.67;
  double elevation_max_deg = 10.67;
  int azimuth_steps = 2170;   ///< firings per revolution (0.166°)
  double min_range = 1.0;     ///< [m]
  double max_range = 80.0;    ///< [m]
  double range_sigma = 0.02;  ///< [m], along the beam
  std::uint32_t seed = 1;
};

/// \brief Axis-aligned box [lo, hi].
struct Box
{
  Eigen::Vector3d lo, hi;
};

/// \brief Vertical cylinder: base centre, radius, height.
struct Cylinder
{
  Eigen::Vector3d base;
  double radius = 0.2, height = 5.0;
};

/// \brief Sphere.
struct Sphere
{
  Eigen::Vector3d centre;
  double radius = 2.0;
};

/// \brief The scanned world: ground z = slope · (x, y) and solids on it.
struct StreetScene
{
  Eigen::Vector2d slope = Eigen::Vector2d(0.01, -0.005);
  std::vector<Box> boxes;
  std::vector<Cylinder> cylinders;
  std::vector<Sphere> spheres;

  double
  groundHeight(double x, double y) const
  {
    return slope.x() * x + slope.y() * y;
  }
};

/// \brief A 200 m street along x: building blocks on both sides (varied setbacks, heights and
///        gaps), parked cars, poles and trees. The same seed gives the same street.
StreetScene
makeStreetScene(std::uint32_t seed = 1);

/// \brief One revolution from `sensor_pose` (sensor frame → world; x forward, z up); points in
///        the sensor frame.
pcl::PointCloud<pcl::PointXYZ>
scanStreet(const StreetScene& scene, const Eigen::Isometry3d& sensor_pose,
           const SpinningScannerSettings& settings = SpinningScannerSettings());

/// \brief Two scans of one street and the transformation that maps the source scan's points
///        into the target scan's frame (target_pose⁻¹ · source_pose).
struct SpinningScanPair
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr source, target;
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity();
  StreetScene scene;
  Eigen::Isometry3d source_pose = Eigen::Isometry3d::Identity(), target_pose = Eigen::Isometry3d::Identity();
};

/// \brief The target scan at the origin (sensor 1.8 m above the ground), the source scan after
///        the vehicle drove `forward` metres and turned `yaw_deg` (a 10 Hz odometry step at
///        about 40 km/h by default). Independent range noise per scan.
SpinningScanPair
makeSpinningScanPair(double forward = 1.2, double yaw_deg = 2.0, std::uint32_t seed = 1,
                     const SpinningScannerSettings& settings = SpinningScannerSettings());

}  // namespace synth
}  // namespace pcl_ls3d
