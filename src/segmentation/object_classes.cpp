/// \file object_classes.cpp
/// \brief Classes of the assembled objects: kind votes, terrain height and plan size.

#include <pcl_ls3d/segmentation/object_classes.h>

#include "terrain_cells.h"

#include <pcl_ls3d/stats/descriptive.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

namespace pcl_ls3d {
namespace segmentation {
namespace {

using detail::planCellOf;
using detail::TerrainCells;
using detail::TerrainPlane;

enum Family
{
  kGround,
  kRough,
  kSurface,
  kLinear,
  kFamilies
};

int
familyOf(SegmentKind k)
{
  switch (k) {
  case SegmentKind::Ground:
    return kGround;
  case SegmentKind::Rough:
    return kRough;
  case SegmentKind::Linear:
    return kLinear;
  default:
    return kSurface;  // solid, wall
  }
}

/// What one object looks like: kind votes, point count, plan moments and box along its axes.
struct ObjectShape
{
  std::size_t votes[kFamilies] = {0, 0, 0, 0};
  std::size_t points = 0;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< first point (moments are relative)
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d sum_sq = Eigen::Matrix2d::Zero();
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();  ///< major plan axis
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;                  ///< along (axis, its normal)
  Eigen::Vector2d box_lo = lo, box_hi = hi;  ///< x, y box (terrain search)
  std::size_t cover = 0;                     ///< linear ones: occupied wire cells

  int
  family() const
  {
    return static_cast<int>(std::max_element(votes, votes + kFamilies) - votes);
  }
  double
  length() const
  {
    return hi.x() - lo.x();
  }
  double
  width() const
  {
    return hi.y() - lo.y();
  }
};

std::vector<ObjectShape>
objectShapes(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
             const std::vector<SegmentKind>& point_kind)
{
  const int n_objects = labels.empty() ? 0 : *std::max_element(labels.begin(), labels.end()) + 1;
  std::vector<ObjectShape> shapes(static_cast<std::size_t>(std::max(0, n_objects)));
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (labels[p] < 0 || !points[p].allFinite())
      continue;
    ObjectShape& s = shapes[static_cast<std::size_t>(labels[p])];
    const Eigen::Vector2d xy = points[p].head<2>().cast<double>();
    if (s.points++ == 0)
      s.origin = xy;
    ++s.votes[familyOf(point_kind[p])];
    const Eigen::Vector2d d = xy - s.origin;
    s.sum += d;
    s.sum_sq += d * d.transpose();
    s.box_lo = s.box_lo.cwiseMin(xy);
    s.box_hi = s.box_hi.cwiseMax(xy);
  }
  for (ObjectShape& s : shapes) {
    const double n = static_cast<double>(s.points);
    if (n < 2.0)
      continue;
    const Eigen::Matrix2d cov = s.sum_sq / n - (s.sum / n) * (s.sum / n).transpose();
    s.axis = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov).eigenvectors().col(1);
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (labels[p] < 0 || !points[p].allFinite())
      continue;
    ObjectShape& s = shapes[static_cast<std::size_t>(labels[p])];
    const Eigen::Vector2d d = points[p].head<2>().cast<double>() - s.origin;
    const Eigen::Vector2d along(d.dot(s.axis), s.axis.x() * d.y() - s.axis.y() * d.x());
    s.lo = s.lo.cwiseMin(along);
    s.hi = s.hi.cwiseMax(along);
  }
  return shapes;
}

/// Plan cells of edge \a cell that the points of each linear-family object occupy: a wire's
/// run along its length, a canopy or a row of roofs seen as a line covers its width too.
void
countLinearCover(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels, double cell,
                 std::vector<ObjectShape>& shapes)
{
  std::vector<std::unordered_set<std::uint64_t>> cells(shapes.size());
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (labels[p] < 0 || !points[p].allFinite())
      continue;
    const auto o = static_cast<std::size_t>(labels[p]);
    if (shapes[o].family() == kLinear)
      cells[o].insert(planCellOf(points[p], cell));
  }
  for (std::size_t o = 0; o < shapes.size(); ++o)
    shapes[o].cover = cells[o].size();
}

/// Per object, its points' z with the slope of its terrain plane taken out.
std::vector<std::vector<double>>
detrendedHeights(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
                 const std::vector<TerrainPlane>& planes)
{
  std::vector<std::vector<double>> heights(planes.size());
  for (std::size_t p = 0; p < points.size(); ++p)
    if (labels[p] >= 0 && points[p].allFinite()) {
      const auto o = static_cast<std::size_t>(labels[p]);
      heights[o].push_back(planes[o].detrended(points[p]));
    }
  return heights;
}

/// Robust ends and middle of an object's detrended z (5th, 50th, 95th percentiles) and the
/// level of its terrain plane (NaN where no ground lies near).
struct Heights
{
  double low, middle, top, terrain;

  bool
  known() const
  {
    return std::isfinite(terrain);
  }
};

/// Poles and lattice towers are taller than wide and hold their points all the way up (a tall
/// narrow building seen from above holds most of them in its roof). A lattice tower's surfaces
/// are about as wide as long in plan, where a piece of wall is thin; a line (a mast with its
/// cross arm) has no width to judge.
bool
standsUpright(const ObjectShape& s, const Heights& h, const ObjectClassSettings& c)
{
  const double vertical = h.top - h.low;
  return vertical >= c.min_building_height && vertical >= c.pole_slenderness * s.length() &&
         h.middle - h.low <= c.pole_mass_height * vertical &&
         (s.family() == kLinear || s.width() >= c.pole_plan_aspect * s.length());
}

/// A ground-like object standing clearly above the other ground around it (\a h's terrain is
/// theirs) is a roof that the ground filter kept (wider than its largest window, or with
/// little terrain around).
bool
raisedAbove(const ObjectShape& s, const Heights& h, const ObjectClassSettings& c)
{
  return h.middle - h.terrain >= c.min_building_height &&  // false for a NaN level
         s.length() * s.width() >= c.min_building_area;
}

bool
carSizedInPlan(const ObjectShape& s, const ObjectClassSettings& c)
{
  return s.length() >= c.car_min_length && s.length() <= c.car_max_length && s.width() >= c.car_min_width &&
         s.width() <= c.car_max_width;
}

/// As wide as a car, at least as long as one and at most car_row_max_length: a car, or a row
/// of cars parked nose to tail that grew into one object (gaps under the growth radius).
bool
carRowInPlan(const ObjectShape& s, const ObjectClassSettings& c)
{
  return s.length() >= c.car_min_length && s.length() <= c.car_row_max_length &&
         s.width() >= c.car_min_width && s.width() <= c.car_max_width;
}

/// Its top at most car_max_height above known terrain.
bool
lowAsACar(const Heights& h, const ObjectClassSettings& c)
{
  return h.known() && h.top - h.terrain <= c.car_max_height;
}

/// Car-sized: low as a car, car-sized in plan.
bool
carSized(const ObjectShape& s, const Heights& h, const ObjectClassSettings& c)
{
  return lowAsACar(h, c) && carSizedInPlan(s, c);
}

ObjectClass
surfaceClass(const ObjectShape& s, const Heights& h, const ObjectClassSettings& c)
{
  const bool known = h.known();
  const double low = h.low - h.terrain, middle = h.middle - h.terrain, top = h.top - h.terrain;
  if (carSized(s, h, c))
    return ObjectClass::Car;
  // A building stands on the terrain: its low points are not far below the ground around it.
  // A surface reaching min_building_height below it is the terrain itself (a wooded ravine
  // grown into one segment, IGN's La Réunion sample).
  const bool standing = !known || low >= -c.min_building_height;
  // Most of a building's points are its roof: its median stands at least half its minimum
  // height up (a shrub layer grown together with the slope under it reaches 2 m with its top
  // only: IGN's target_cloud_crop).
  const bool roof_up = !known || middle >= 0.5 * c.min_building_height;
  if ((!known || top >= c.min_building_height) && standing && roof_up &&
      s.length() * s.width() >= c.min_building_area)
    return ObjectClass::Building;
  return ObjectClass::Unclassified;
}

ObjectClass
linearClass(const ObjectShape& s, double low, const ObjectClassSettings& c)
{
  const double thin = c.max_wire_cover * s.length() / c.wire_cell;
  if (low >= c.min_wire_height && s.length() >= c.min_wire_length &&  // false for NaN
      static_cast<double>(s.cover) <= thin)
    return ObjectClass::Wire;
  return ObjectClass::Unclassified;
}

}  // namespace

ObjectClass
classOf(int label, const std::vector<ObjectClass>& object_class)
{
  return label >= 0 && static_cast<std::size_t>(label) < object_class.size()
             ? object_class[static_cast<std::size_t>(label)]
             : ObjectClass::Unclassified;
}

const char*
toString(ObjectClass c)
{
  switch (c) {
  case ObjectClass::Ground:
    return "ground";
  case ObjectClass::Building:
    return "building";
  case ObjectClass::Vegetation:
    return "vegetation";
  case ObjectClass::Wire:
    return "wire";
  case ObjectClass::Pole:
    return "pole";
  case ObjectClass::Car:
    return "car";
  default:
    return "unclassified";
  }
}

std::uint8_t
lasCode(ObjectClass c)
{
  switch (c) {
  case ObjectClass::Ground:
    return 2;
  case ObjectClass::Building:
    return 6;
  case ObjectClass::Vegetation:
    return 5;
  case ObjectClass::Wire:
    return 14;
  case ObjectClass::Pole:
    return 15;
  case ObjectClass::Car:
    return 64;
  default:
    return 1;
  }
}

bool
objectClassFromLasCode(int code, ObjectClass& c)
{
  for (const ObjectClass k : kObjectClasses)
    if (lasCode(k) == code) {
      c = k;
      return true;
    }
  return false;
}

std::string
describeLasCodes()
{
  std::string text;
  for (const ObjectClass k :
       {ObjectClass::Ground, ObjectClass::Building, ObjectClass::Vegetation, ObjectClass::Wire,
        ObjectClass::Pole, ObjectClass::Car, ObjectClass::Unclassified})
    text += (text.empty() ? "" : ", ") + std::to_string(lasCode(k)) + " " + toString(k);
  return text;
}

namespace {

/// Per object: may it be a car (or a row of cars) although it is rough? Its returns are known,
/// at most car_max_multiple_return_share of its (finite) points come from pulses with several
/// returns and it is a car or a row of cars in plan (its height is judged once its terrain is
/// known). All false when \a multiple_return is empty.
std::vector<char>
opaqueCarOrRow(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
               const std::vector<char>& multiple_return, const std::vector<ObjectShape>& shapes,
               const ObjectClassSettings& c)
{
  std::vector<char> out(shapes.size(), 0);
  if (multiple_return.empty())
    return out;
  std::vector<std::size_t> multiple(shapes.size(), 0);
  for (std::size_t p = 0; p < points.size(); ++p)
    if (labels[p] >= 0 && points[p].allFinite() && multiple_return[p])
      ++multiple[static_cast<std::size_t>(labels[p])];
  for (std::size_t o = 0; o < shapes.size(); ++o)
    out[o] = shapes[o].points > 0 && shapes[o].family() == kRough && carRowInPlan(shapes[o], c) &&
             static_cast<double>(multiple[o]) <=
                 c.car_max_multiple_return_share * static_cast<double>(shapes[o].points);
  return out;
}

}  // namespace

bool
recordsReturns(const std::vector<std::uint8_t>& number_of_returns)
{
  return std::any_of(number_of_returns.begin(), number_of_returns.end(),
                     [](std::uint8_t r) { return r > 1; });
}

std::vector<ObjectClass>
classifyObjects(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
                const std::vector<SegmentKind>& point_kind, const std::vector<char>& ground,
                const ObjectClassSettings& settings, const std::vector<char>& multiple_return)
{
  if (labels.size() != points.size() || point_kind.size() != points.size() ||
      ground.size() != points.size() || (!multiple_return.empty() && multiple_return.size() != points.size()))
    return {};
  std::vector<ObjectShape> shapes = objectShapes(points, labels, point_kind);
  countLinearCover(points, labels, settings.wire_cell, shapes);
  const std::vector<char> may_be_car = opaqueCarOrRow(points, labels, multiple_return, shapes, settings);
  const TerrainCells terrain(points, labels, ground, settings.terrain_cell);
  std::vector<TerrainPlane> planes(shapes.size());
  for (std::size_t o = 0; o < shapes.size(); ++o)  // rough: vegetation unless it may be a car
    if (shapes[o].points > 0 && (shapes[o].family() != kRough || may_be_car[o]))
      planes[o] = terrain.planeAround(shapes[o].box_lo, shapes[o].box_hi, settings.terrain_margin,
                                      shapes[o].family() == kGround ? static_cast<int>(o) : -2);
  const std::vector<std::vector<double>> detrended = detrendedHeights(points, labels, planes);
  std::vector<ObjectClass> classes(shapes.size(), ObjectClass::Unclassified);
  for (std::size_t o = 0; o < shapes.size(); ++o) {
    const ObjectShape& s = shapes[o];
    if (s.points == 0)
      continue;
    const int family = s.family();
    if (family == kRough && !may_be_car[o]) {
      classes[o] = ObjectClass::Vegetation;
      continue;
    }
    // Heights along the terrain's slope; the ground family against the other ground only.
    const std::vector<double> z = stats::quantiles(detrended[o], {0.05, 0.5, 0.95});
    const Heights h{z[0], z[1], z[2], planes[o].level};
    if (family == kRough) {  // opaque, a car or a row of cars in plan: cars if low enough
      classes[o] = lowAsACar(h, settings) ? ObjectClass::Car : ObjectClass::Vegetation;
      continue;
    }
    if (family == kGround) {
      classes[o] = raisedAbove(s, h, settings) ? ObjectClass::Building : ObjectClass::Ground;
      continue;
    }
    if (standsUpright(s, h, settings))
      classes[o] = ObjectClass::Pole;
    else
      classes[o] =
          family == kSurface ? surfaceClass(s, h, settings) : linearClass(s, h.low - h.terrain, settings);
  }
  return classes;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
