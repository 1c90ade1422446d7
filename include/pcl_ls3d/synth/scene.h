#pragma once
/// \file scene.h
/// \brief A labelled airborne scene for segmentation: terrain, flat, gable and hip roofed
///        buildings (roofs + sparse walls), trees and shrubs with multiple returns, a power line
///        (lattice towers + catenary wires) and cars, with ASPRS classes, an object id for every
///        point (the terrain is one object) and a plane id for every roof point.
///
/// Classes (PointLiDAR::classification): 2 ground, 6 building (roofs and walls), 3 / 4 / 5 low /
/// medium / high vegetation by the point's height above the terrain (< low_max, < medium_max,
/// above), 14 wire conductor, 15 transmission tower, cars `car_class` (default 64; ASPRS
/// reserves 64–255 as user-definable).
///
/// Sampling: `density` pulses per m² at uniform random (x, y). Each pulse hits, from the top, a
/// tree/shrub crown (an ellipsoid: a first return in the upper crown, possibly one inside it, and
/// possibly a last return on the ground: 1–3 returns with one gps_time), else a roof, else a car
/// top, else the terrain. Walls, towers and wires are sampled separately (walls at
/// wall_density_ratio·density per m² of wall, towers/wires every `line_spacing` metres along
/// their members), because pulses from above rarely hit them. Isotropic noise on every point.
/// Clouds hold local coordinates; written coordinates = local + origin.

#include <pcl_ls3d/point_types.h>
#include <pcl_ls3d/synth/buildings.h>

#include <pcl/point_cloud.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace synth {

enum class ObjectType : std::uint8_t
{
  BUILDING = 0,
  TREE,
  SHRUB,
  CAR,
  TOWER,
  WIRE,
  GROUND
};

/// "building", "tree", "shrub", "car", "tower", "wire", "ground".
const char*
toString(ObjectType t);

/// \brief One generated object (local coordinates).
struct SceneObject
{
  int id = 0;  ///< index in LabelledScene::objects
  ObjectType type = ObjectType::BUILDING;
  std::uint8_t classification = 0;                     ///< class of its points (vegetation: dominant class)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< footprint centre on the ground / wire start
  Eigen::Vector3d size = Eigen::Vector3d::Zero();      ///< extent (length, width, height) [m]
  double heading = 0.0;                                ///< orientation of the length axis [rad]
  std::size_t point_count = 0;
};

/// \brief One roof plane of a generated building.
struct RoofPlane
{
  int object = 0;  ///< the building's index in LabelledScene::objects
  RoofType roof = RoofType::FLAT;
  int index = 0;  ///< Building::roofPlane() of its points
  std::size_t point_count = 0;
};

/// \brief Settings of makeScene().
struct SceneSettings
{
  std::uint32_t seed = 1;
  double size_x = 200.0, size_y = 200.0;   ///< extent, centred on the origin [m]
  double density = 8.0;                    ///< pulses per m²
  double noise_sigma = 0.03;               ///< isotropic noise per axis [m]
  double relief = 6.0, wavelength = 80.0;  ///< Terrain
  bool buildings = true;
  BuildingSettings building_settings = defaultSceneBuildings();
  double wall_density_ratio = 0.1;  ///< wall points per m² relative to density (sparse walls)
  double trees_per_hectare = 30.0;
  double shrubs_per_hectare = 30.0;
  double low_max = 0.5, medium_max = 2.0;  ///< vegetation class limits above ground [m]
  bool power_line = true;
  int towers = 3;              ///< along a line across the scene
  int wires = 3;               ///< conductors per span
  double tower_height = 25.0;  ///< [m]
  double wire_sag = 0.03;      ///< sag / span length
  double line_spacing = 0.3;   ///< point spacing along wires and tower members [m]
  double cars_per_hectare = 10.0;
  std::uint8_t car_class = 64;  ///< user-definable class for cars
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();

  static BuildingSettings
  defaultSceneBuildings()
  {
    BuildingSettings b;
    b.per_hectare = 5.0;
    b.gable_fraction = 1.0 / 3.0;
    b.hip_fraction = 1.0 / 3.0;
    return b;
  }

  bool
  isValid(std::string* why = nullptr) const;
};

/// \brief The labelled cloud and what is in it.
struct LabelledScene
{
  pcl::PointCloud<PointLiDAR>::Ptr cloud;
  std::vector<SceneObject> objects;
  std::vector<int> object_id;     ///< per point: index in objects (the terrain is one GROUND object)
  std::vector<RoofPlane> planes;  ///< roof planes of all buildings
  std::vector<int> plane_id;      ///< per point: index in planes for roof points, −1 otherwise
  std::shared_ptr<const SurfaceModel> surface;  ///< terrain + buildings
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();

  /// Points per classification code.
  std::map<int, std::size_t>
  classCounts() const;
};

/// Generates the scene; deterministic in the seed. Invalid settings: PCL_ERROR, empty cloud.
LabelledScene
makeScene(const SceneSettings& settings);

}  // namespace synth
}  // namespace pcl_ls3d
