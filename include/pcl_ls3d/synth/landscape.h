#pragma once
/// \file landscape.h
/// \brief What an airborne pulse from above hits, for the strip blocks: the rolling default
///        (terrain + buildings), an urban scene (Zuo et al. 2012, Hebei: dense buildings, trees,
///        straight roads free of both) and a mountainous one (Henan: terraced ground, scarps,
///        isolated trees, a few low buildings).
///
/// A pulse at (x, y) inside a tree crown (an ellipsoid of radius r and depth 0.6 × the tree's
/// height) reaches the ground with probability `penetration` (class 2), else it returns from
/// the crown 0–1 m below its top (class 5, high vegetation: not a stable surface). Otherwise it
/// hits a roof (class 6) or the ground (class 2; roads are ground). Roads: a grid of straight
/// corridors (two families at right angles, `road_spacing` apart, `road_width` wide) kept free
/// of buildings and trees.

#include <pcl_ls3d/synth/buildings.h>
#include <pcl_ls3d/synth/landforms.h>
#include <pcl_ls3d/synth/random.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace synth {

enum class LandscapeType : std::uint8_t
{
  ROLLING = 0,
  URBAN = 1,
  MOUNTAIN = 2
};

/// "rolling", "urban", "mountain".
const char*
toString(LandscapeType type);

/// \brief The parts of a scene beyond terrain and buildings (unused by ROLLING).
struct LandscapeSettings
{
  LandscapeType type = LandscapeType::ROLLING;
  LandformSettings landforms;
  double trees_per_hectare = 0.0;
  double min_crown_radius = 2.0, max_crown_radius = 5.0;  ///< [m]
  double min_tree_height = 6.0, max_tree_height = 15.0;   ///< top above the ground [m]
  double penetration = 0.3;                               ///< share of crown pulses that reach the ground
  double road_spacing = 0.0;                              ///< 0 = no roads [m]
  double road_width = 12.0;                               ///< [m]
  double road_heading = 0.35;  ///< direction of the first road family from +x [rad]

  bool
  isValid(std::string* why = nullptr) const;
};

/// \brief One return: height, ASPRS class and a plausible intensity.
struct Hit
{
  double z = 0.0;
  std::uint8_t classification = 2;
  float intensity_base = 50.0f;
};

/// \brief Terrain with landforms, buildings and trees.
class Landscape
{
public:
  /// Builds the scene over `region` (buildings from `buildings`, scarps and trees from `seed`).
  Landscape(const Terrain& terrain, const LandscapeSettings& settings, bool buildings,
            const BuildingSettings& building_settings, const Eigen::AlignedBox2d& region, std::uint32_t seed);
  ~Landscape();

  /// The return of a pulse from above at (x, y). Draws from `rng` only where a tree stands.
  Hit
  hit(double x, double y, Random& rng) const;

  /// Ground height (terrain with landforms) at (x, y).
  double
  groundHeight(double x, double y) const;

  const Ground&
  ground() const
  {
    return ground_;
  }
  /// Terrain + buildings without landforms and trees (the ROLLING true surface).
  const std::shared_ptr<const SurfaceModel>&
  surface() const
  {
    return surface_;
  }
  /// True when (x, y) lies within `margin` of a road corridor.
  bool
  onRoad(double x, double y, double margin = 0.0) const;
  std::size_t
  treeCount() const;

private:
  struct Trees;
  LandscapeSettings settings_;
  Ground ground_;
  std::shared_ptr<const SurfaceModel> surface_;
  std::unique_ptr<Trees> trees_;
};

}  // namespace synth
}  // namespace pcl_ls3d
