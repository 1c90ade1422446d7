#pragma once
/// \file buildings.h
/// \brief Rectangular buildings with flat, gable or hip roofs, placed on a Terrain, and a grid
///        index that answers "which roof is above (x, y)" in O(1).

#include <pcl_ls3d/synth/terrain.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace synth {

enum class RoofType : std::uint8_t
{
  FLAT = 0,
  GABLE = 1,
  HIP = 2
};

/// \brief Number of roof planes: 1 flat, 2 gable, 4 hip.
int
roofPlaneCount(RoofType roof);

/// \brief An oriented rectangular block. Local axes: u along `heading` (the ridge), v across.
///        Roof height: eave_z on a flat roof; eave_z + ridge_rise·(1 − |v|/(width/2)) on a gable
///        roof; on a hip roof, with all four planes at the gable's pitch,
///        eave_z + ridge_rise·min(width/2 − |v|, length/2 − |u|)/(width/2) (ridge length
///        length − width). Walls run from the terrain up to the roof edge.
struct Building
{
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< footprint centre [m]
  double length = 20.0;                              ///< footprint extent along u (ridge direction) [m]
  double width = 10.0;                               ///< footprint extent along v [m]
  double heading = 0.0;                              ///< angle of u from +x [rad]
  double eave_z = 0.0;                               ///< absolute height of the eave (whole flat roof) [m]
  double ridge_rise = 0.0;                           ///< ridge above eave, gable and hip [m]
  RoofType roof = RoofType::FLAT;

  /// (u, v) of a horizontal position.
  Eigen::Vector2d
  toLocal(double x, double y) const;

  /// True if (x, y) lies inside the footprint grown by `margin` (negative shrinks it).
  bool
  contains(double x, double y, double margin = 0.0) const;

  /// Roof height at (x, y) (meaningful inside the footprint).
  double
  roofHeight(double x, double y) const;

  /// Roof plane under (x, y), 0..roofPlaneCount(roof)−1: gable 0 for v ≥ 0, 1 for v < 0; hip
  /// the same on the long sides, 2 (u ≥ 0) and 3 (u < 0) on the hipped ends.
  int
  roofPlane(double x, double y) const;

  /// Radius of the circle around the footprint.
  double
  radius() const;
};

/// \brief Placement settings for placeBuildings().
struct BuildingSettings
{
  double per_hectare = 2.0;                     ///< expected buildings per 10 000 m²
  double min_length = 10.0, max_length = 30.0;  ///< [m]
  double min_width = 8.0, max_width = 15.0;     ///< [m]
  double min_eave = 3.0, max_eave = 9.0;        ///< eave above the highest footprint terrain [m]
  double min_rise = 2.0, max_rise = 4.0;        ///< gable ridge rise [m]
  double gable_fraction = 0.5;                  ///< share of gable roofs
  double hip_fraction = 0.0;                    ///< share of hip roofs (the rest is flat)
  double gap = 6.0;                             ///< minimum clear distance between buildings [m]
};

/// \brief Buildings plus a uniform-grid index over their footprints.
class BuildingSet
{
public:
  BuildingSet() = default;
  explicit BuildingSet(std::vector<Building> buildings, double cell = 25.0);

  /// Index of the building whose footprint (grown by margin) contains (x, y), or −1.
  int
  find(double x, double y, double margin = 0.0) const;

  const std::vector<Building>&
  buildings() const
  {
    return buildings_;
  }
  bool
  empty() const
  {
    return buildings_.empty();
  }

private:
  std::vector<Building> buildings_;
  std::vector<std::vector<int>> cells_;
  Eigen::Vector2d min_ = Eigen::Vector2d::Zero();
  double cell_ = 25.0;
  int nx_ = 0, ny_ = 0;
  double max_margin_ = 2.0;  ///< cells are filled with footprints grown by this much
};

/// \brief Randomly places non-overlapping buildings inside `region` (rejection sampling with
///        settings.gap clearance; count = round(per_hectare · area / 1e4), fewer if the region is
///        full). Each eave is set above the highest terrain point of its footprint.
std::vector<Building>
placeBuildings(const Terrain& terrain, const Eigen::AlignedBox2d& region, const BuildingSettings& settings,
               std::uint32_t seed);

/// \brief The true surface seen from above: roofs where there is a building, terrain elsewhere.
class SurfaceModel
{
public:
  SurfaceModel(Terrain terrain, BuildingSet buildings)
      : terrain_(std::move(terrain)), buildings_(std::move(buildings))
  {}

  /// Top surface height; `building` receives the building index or −1 for terrain.
  double
  height(double x, double y, int* building = nullptr) const;

  const Terrain&
  terrain() const
  {
    return terrain_;
  }
  const BuildingSet&
  buildings() const
  {
    return buildings_;
  }

private:
  Terrain terrain_;
  BuildingSet buildings_;
};

}  // namespace synth
}  // namespace pcl_ls3d
