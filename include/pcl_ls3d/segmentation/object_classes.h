#pragma once
/// \file object_classes.h
/// \brief What each object of IMRG's object level is — ground, building, vegetation, wire,
///        pole, car or unclassified — from the kinds of the segments it was assembled from
///        (segment_kinds.h), its height above the terrain and its size in plan. PCL-free.
///
/// Per object, the points vote with the kind of their segment before any join (ground; rough;
/// solid or wall; linear) and the largest vote decides the family:
///  - ground: Ground, unless its median stands min_building_height above the ground around it
///    (the level from the cells near it whose lowest ground-filter point is not its own, the
///    slope from all of them) and its plan box covers min_building_area: a roof wider than the
///    ground filter's largest window, which the filter kept, is a Building;
///  - rough: Vegetation (crowns, hedges, grass detached from the ground), except one as low
///    as a car (as below) and as wide as one, car_min_length..car_row_max_length long (a car,
///    or a row of cars parked nose to tail grown into one object), of which at most
///    car_max_multiple_return_share of the points come from pulses with several returns, when
///    the returns are known: a Car (a car body stops the pulse; a shrub of its size lets part
///    of it through). Parked cars scan as rough as shrubs at 10–20 points/m²;
///  - surface (solid, wall) or linear, standing upright — vertical extent at least
///    min_building_height and pole_slenderness × its plan length, median z in the lower
///    pole_mass_height of that extent (points all the way up: a tall building seen from above
///    has most in its roof), and a surface one at least pole_plan_aspect × as wide as long (a
///    lattice tower; a piece of wall is thin): Pole;
///  - surface: Car when car-sized (top at most car_max_height above the terrain,
///    car_min_length..car_max_length long, car_min_width..car_max_width wide); Building when
///    its top is at least min_building_height above the terrain, its median at least half
///    that (most of a building's points are its roof; a shrub layer grown together with the
///    slope under it reaches that height with its top only), its low points (5th
///    percentile) not min_building_height below it (a building stands on the terrain; a
///    surface reaching below it is terrain grown into one segment: a wooded ravine) and its
///    plan box covers at least min_building_area; else Unclassified (a low wall, a shelter's
///    roof piece);
///  - linear: Wire when even its low points hang min_wire_height above the terrain, it is at
///    least min_wire_length long and thin (its points occupy at most max_wire_cover × length /
///    wire_cell plan cells of edge wire_cell: a canopy edge or a row of roofs grown as a line
///    covers its width too); else Unclassified (a kerb, a fence).
/// Plan length and width are the extents along the object's principal plan axes. The terrain
/// is looked for around its x–y box, in the lowest ground-filter point per terrain_cell cell
/// within terrain_margin of that box: a plane whose slope is the least-squares one of those
/// points (refitted twice without the cells more than 3 robust sigmas, at least 0.5 m, off it;
/// flat where they spread less than one cell, as a standard deviation, across) and whose level
/// is their median along that slope. Heights are taken above that plane, so that on a
/// hillside the upper half of the slope is no roof over the lower half. Where no ground point
/// lies that close the height is unknown: a surface is then a Building if its plan box covers
/// min_building_area (a roof-only crop; a car there is called a building too), a line is no
/// wire. Heights use robust ends and middle: low, median and top are the 5th, 50th and 95th
/// percentiles of the object's z with the terrain's slope taken out. Rough objects take a
/// terrain only when they may be a car (returns known, a car or a row of cars in plan);
/// without one they are vegetation whatever their height.
/// Lengths are metres (cloud units): car and building sizes are physical, not relative to the
/// spacing. Non-finite points are skipped.

#include <pcl_ls3d/segmentation/segment_kinds.h>

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {

enum class ObjectClass : std::uint8_t
{
  Unclassified,
  Ground,
  Building,
  Vegetation,
  Wire,
  Pole,
  Car
};

/// \brief Every class, in the order of the enum.
constexpr ObjectClass kObjectClasses[] = {
    ObjectClass::Unclassified, ObjectClass::Ground, ObjectClass::Building, ObjectClass::Vegetation,
    ObjectClass::Wire,         ObjectClass::Pole,   ObjectClass::Car};

/// \brief "unclassified", "ground", "building", "vegetation", "wire", "pole", "car".
const char*
toString(ObjectClass c);

/// \brief The LAS code written for a class: 1 unclassified, 2 ground, 6 building, 5 (high)
///        vegetation, 14 wire conductor, 15 transmission tower (poles and towers), 64 car (a
///        user-definable code, as pcl_ls3d_synth's cars; ASPRS has no car class).
std::uint8_t
lasCode(ObjectClass c);

/// \brief The class written as \a code (lasCode()); false for any other code.
bool
objectClassFromLasCode(int code, ObjectClass& c);

/// \brief "2 ground, 6 building, 5 vegetation, 14 wire, 15 pole, 64 car, 1 unclassified": the
///        codes as written, for reports and help texts.
std::string
describeLasCodes();

/// \brief The class of object \a label: Unclassified for −1 or a label past \a object_class.
ObjectClass
classOf(int label, const std::vector<ObjectClass>& object_class);

/// \brief Thresholds of classifyObjects(); lengths in metres (cloud units).
struct ObjectClassSettings
{
  double terrain_cell = 2.0;                          ///< cell of the grid of lowest ground points
  double terrain_margin = 5.0;                        ///< terrain sought this far around the plan box
  double min_building_height = 2.0;                   ///< a building's top above the terrain
  double min_building_area = 6.0;                     ///< a building's plan box (length × width)
  double car_max_height = 3.0;                        ///< a car's top above the terrain (vans included)
  double car_min_length = 2.5, car_max_length = 7.0;  ///< a car's plan length
  double car_min_width = 1.2, car_max_width = 3.0;    ///< ... and width (a low wall is thinner)
  /// A rough object as wide as a car may be a row of cars parked nose to tail up to this long
  /// (four or five cars; a longer opaque strip is a dense hedge).
  double car_row_max_length = 25.0;
  /// A rough car-sized object (or row) is a car when at most this share of its points had more
  /// than one return (only with the returns known). 0.2: between the cars (0.00–0.08) and the
  /// car-sized shrubs (0.25 and more) of the tuning tiles 77050_627755 and 77055_627755
  /// (docs/BENCHMARKS.md).
  double car_max_multiple_return_share = 0.2;
  double min_wire_height = 2.5;   ///< a wire's low points above the terrain
  double min_wire_length = 7.0;   ///< a wire's plan length (longer than a car)
  double wire_cell = 0.5;         ///< a wire covers at most max_wire_cover × its length
  double max_wire_cover = 2.0;    ///< / wire_cell plan cells of this edge (it is thin)
  double pole_slenderness = 1.5;  ///< a pole's vertical extent / plan length, at least
  double pole_plan_aspect = 0.5;  ///< ... a surface one's plan width / length, at least
                                  ///< (a lattice tower; a piece of wall is thin)
  double pole_mass_height = 0.7;  ///< ... and its median z at most this far up its extent
};

/// \brief True when \a number_of_returns (per point, as LAS NumberOfReturns) records returns:
///        some pulse had more than one. Data without returns store 1 (or 0) everywhere.
bool
recordsReturns(const std::vector<std::uint8_t>& number_of_returns);

/// \brief The class of every object.
/// \param[in] points coordinates per point
/// \param[in] labels object per point (dense 0..n−1, −1 none)
/// \param[in] point_kind per point: kind of its segment before the assembly joined any
/// \param[in] ground per point: 1 if the ground filter keeps it
/// \param[in] multiple_return per point: 1 if its pulse had more than one return (LAS
///            NumberOfReturns > 1); empty when the data do not record returns (pass empty,
///            not all 0, for such data: all 0 says every pulse was stopped by the first surface)
/// \return per object (index = label): its class; empty when the sizes differ
std::vector<ObjectClass>
classifyObjects(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
                const std::vector<SegmentKind>& point_kind, const std::vector<char>& ground,
                const ObjectClassSettings& settings, const std::vector<char>& multiple_return = {});

}  // namespace segmentation
}  // namespace pcl_ls3d
