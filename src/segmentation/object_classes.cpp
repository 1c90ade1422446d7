/// \file object_classes.cpp
/// \brief Classes of the assembled objects: kind votes, terrain height and plan size.

#include <pcl_ls3d/segmentation/object_classes.h>

#include <pcl_ls3d/common/voxel_index.h>
#include <pcl_ls3d/stats/descriptive.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace pcl_ls3d {
namespace segmentation {
namespace {

enum Family { kGround, kRough, kSurface, kLinear, kFamilies };

int
familyOf(SegmentKind k)
{
  switch (k) {
  case SegmentKind::Ground: return kGround;
  case SegmentKind::Rough: return kRough;
  case SegmentKind::Linear: return kLinear;
  default: return kSurface;  // solid, wall
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
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();   ///< major plan axis
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;                          ///< along (axis, its normal)
  Eigen::Vector2d box_lo = lo, box_hi = hi;          ///< x, y box (terrain search)
  std::size_t cover = 0;                             ///< linear ones: occupied wire cells

  int family() const
  {
    return static_cast<int>(std::max_element(votes, votes + kFamilies) - votes);
  }
  double length() const { return hi.x() - lo.x(); }
  double width() const { return hi.y() - lo.y(); }
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

/// The hash key of the plan cell of edge \a cell holding \a p.
std::uint64_t
planCellOf(const Eigen::Vector3f& p, double cell)
{
  return planCellKey(planCellCoordinate(p.x(), cell), planCellCoordinate(p.y(), cell));
}

/// Plan cells of edge \a cell that the points of each linear-family object occupy: a wire's
/// run along its length, a canopy or a row of roofs seen as a line covers its width too.
void
countLinearCover(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
                 double cell, std::vector<ObjectShape>& shapes)
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

/// The terrain around an object as a plane: z = level + tilt · (xy − centre). Where no ground
/// lies near, level is NaN and tilt 0.
struct TerrainPlane
{
  double level = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector2d tilt = Eigen::Vector2d::Zero();
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();

  /// z with the terrain's slope taken out: its height above the terrain is detrended − level.
  double detrended(const Eigen::Vector3f& p) const
  {
    return p.z() - tilt.dot(p.head<2>().cast<double>() - centre);
  }
};

/// The lowest ground-filter point per plan cell and the object it belongs to (−1: none): the
/// terrain under and around an object, and what the other ground objects show around a
/// ground object.
class TerrainCells
{
public:
  TerrainCells(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
               const std::vector<char>& ground, double cell)
  : cell_(cell)
  {
    for (std::size_t p = 0; p < points.size(); ++p) {
      if (!ground[p] || !points[p].allFinite())
        continue;
      const Lowest here{points[p], labels[p]};
      const auto [it, fresh] = cells_.try_emplace(planCellOf(points[p], cell_), here);
      if (!fresh && here.point.z() < it->second.point.z())
        it->second = here;
    }
  }

  /// The terrain plane around the object's plan box (cells within \a margin of it): its slope
  /// from all of them, its level the median over the cells whose lowest point is not of object
  /// \a except (−2: take all).
  TerrainPlane planeAround(const ObjectShape& s, double margin, int except) const
  {
    const std::vector<Lowest> near = cellsNear(s, margin);
    TerrainPlane plane;
    plane.centre = 0.5 * (s.box_lo + s.box_hi);
    plane.tilt = robustSlope(near, plane.centre);
    std::vector<double> levels;
    for (const Lowest& l : near)
      if (l.object != except)
        levels.push_back(plane.detrended(l.point));
    plane.level = stats::median(std::move(levels));
    return plane;
  }

private:
  struct Lowest
  {
    Eigen::Vector3f point;
    int object;
  };

  std::vector<Lowest> cellsNear(const ObjectShape& s, double margin) const
  {
    const std::int64_t x0 = planCellCoordinate(s.box_lo.x() - margin, cell_);
    const std::int64_t x1 = planCellCoordinate(s.box_hi.x() + margin, cell_);
    const std::int64_t y0 = planCellCoordinate(s.box_lo.y() - margin, cell_);
    const std::int64_t y1 = planCellCoordinate(s.box_hi.y() + margin, cell_);
    std::vector<Lowest> near;
    // Scan the smaller of the box's cells and the occupied cells.
    if (static_cast<double>(x1 - x0 + 1) * static_cast<double>(y1 - y0 + 1) >
        static_cast<double>(cells_.size())) {
      for (const auto& [key, lowest] : cells_) {
        const std::int64_t x = static_cast<std::int32_t>(key >> 32);
        const std::int64_t y = static_cast<std::int32_t>(key & 0xffffffffu);
        if (x >= x0 && x <= x1 && y >= y0 && y <= y1)
          near.push_back(lowest);
      }
    }
    else {
      for (std::int64_t x = x0; x <= x1; ++x)
        for (std::int64_t y = y0; y <= y1; ++y)
          if (const auto it = cells_.find(planCellKey(x, y)); it != cells_.end())
            near.push_back(it->second);
    }
    return near;
  }

  /// Slope of the least-squares plane through the cells' lowest points, refitted twice
  /// without the cells more than 3 robust sigmas (at least half a metre) off it: roofs the
  /// filter kept and holes do not tilt it. Zero where the cells span less than two cells
  /// across in some direction (a strip along a road tells nothing of the slope across it).
  Eigen::Vector2d robustSlope(const std::vector<Lowest>& near, const Eigen::Vector2d& centre) const
  {
    std::vector<char> kept(near.size(), 1);
    Eigen::Vector3d plane = Eigen::Vector3d::Zero();  // a + b·dx + c·dy
    for (int pass = 0; pass < 3; ++pass) {
      Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
      Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
      for (std::size_t i = 0; i < near.size(); ++i)
        if (kept[i]) {
          const Eigen::Vector2d d = near[i].point.head<2>().cast<double>() - centre;
          const Eigen::Vector3d row(1.0, d.x(), d.y());
          normal += row * row.transpose();
          rhs += row * near[i].point.z();
        }
      if (!spansTwoCells(normal))
        return Eigen::Vector2d::Zero();
      plane = normal.ldlt().solve(rhs);
      std::vector<double> residuals(near.size());
      for (std::size_t i = 0; i < near.size(); ++i) {
        const Eigen::Vector2d d = near[i].point.head<2>().cast<double>() - centre;
        residuals[i] = near[i].point.z() - plane.dot(Eigen::Vector3d(1.0, d.x(), d.y()));
      }
      const double limit = std::max(0.5, 3.0 * 1.4826 * stats::mad(residuals));
      for (std::size_t i = 0; i < near.size(); ++i)
        kept[i] = std::abs(residuals[i]) <= limit;
    }
    return plane.tail<2>();
  }

  /// The normal matrix's points spread at least two cells (standard deviation one cell) across.
  bool spansTwoCells(const Eigen::Matrix3d& normal) const
  {
    const double n = normal(0, 0);
    if (n < 6.0)
      return false;
    const Eigen::Vector2d mean(normal(0, 1) / n, normal(0, 2) / n);
    const Eigen::Matrix2d spread = normal.bottomRightCorner<2, 2>() / n - mean * mean.transpose();
    return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(spread, Eigen::EigenvaluesOnly)
               .eigenvalues()(0) >= cell_ * cell_;
  }

  double cell_;
  std::unordered_map<std::uint64_t, Lowest> cells_;
};

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

/// Poles and lattice towers are taller than wide and hold their points all the way up (a tall
/// narrow building seen from above holds most of them in its roof). A lattice tower's surfaces
/// are about as wide as long in plan, where a piece of wall is thin; a line (a mast with its
/// cross arm) has no width to judge.
bool
standsUpright(const ObjectShape& s, double low, double middle, double top,
              const ObjectClassSettings& c)
{
  const double vertical = top - low;
  return vertical >= c.min_building_height && vertical >= c.pole_slenderness * s.length() &&
         middle - low <= c.pole_mass_height * vertical &&
         (s.family() == kLinear || s.width() >= c.pole_plan_aspect * s.length());
}

/// A ground-like object standing clearly above the other ground around it is a roof that the
/// ground filter kept (wider than its largest window, or with little terrain around).
bool
raisedAbove(const ObjectShape& s, double middle, double others, const ObjectClassSettings& c)
{
  return middle - others >= c.min_building_height &&  // false for a NaN level
         s.length() * s.width() >= c.min_building_area;
}

ObjectClass
surfaceClass(const ObjectShape& s, double low, double middle, double top, double level,
             const ObjectClassSettings& c)
{
  const bool known = std::isfinite(level);
  if (known && top - level <= c.car_max_height && s.length() >= c.car_min_length &&
      s.length() <= c.car_max_length && s.width() >= c.car_min_width &&
      s.width() <= c.car_max_width)
    return ObjectClass::Car;
  // A building stands on the terrain: its low points are not far below the ground around it.
  // A surface reaching min_building_height below it is the terrain itself (a wooded ravine
  // grown into one segment, IGN's La Réunion sample).
  const bool standing = !known || low - level >= -c.min_building_height;
  // Most of a building's points are its roof: its median stands at least half its minimum
  // height up (a shrub layer grown together with the slope under it reaches 2 m with its top
  // only: IGN's target_cloud_crop).
  const bool roof_up = !known || middle - level >= 0.5 * c.min_building_height;
  if ((!known || top - level >= c.min_building_height) && standing && roof_up &&
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

const char*
toString(ObjectClass c)
{
  switch (c) {
  case ObjectClass::Ground: return "ground";
  case ObjectClass::Building: return "building";
  case ObjectClass::Vegetation: return "vegetation";
  case ObjectClass::Wire: return "wire";
  case ObjectClass::Pole: return "pole";
  case ObjectClass::Car: return "car";
  default: return "unclassified";
  }
}

std::uint8_t
lasCode(ObjectClass c)
{
  switch (c) {
  case ObjectClass::Ground: return 2;
  case ObjectClass::Building: return 6;
  case ObjectClass::Vegetation: return 5;
  case ObjectClass::Wire: return 14;
  case ObjectClass::Pole: return 15;
  case ObjectClass::Car: return 64;
  default: return 1;
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
  for (const ObjectClass k : {ObjectClass::Ground, ObjectClass::Building, ObjectClass::Vegetation,
                              ObjectClass::Wire, ObjectClass::Pole, ObjectClass::Car,
                              ObjectClass::Unclassified})
    text += (text.empty() ? "" : ", ") + std::to_string(lasCode(k)) + " " + toString(k);
  return text;
}

std::vector<ObjectClass>
classifyObjects(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
                const std::vector<SegmentKind>& point_kind, const std::vector<char>& ground,
                const ObjectClassSettings& settings)
{
  if (labels.size() != points.size() || point_kind.size() != points.size() ||
      ground.size() != points.size())
    return {};
  std::vector<ObjectShape> shapes = objectShapes(points, labels, point_kind);
  countLinearCover(points, labels, settings.wire_cell, shapes);
  const TerrainCells terrain(points, labels, ground, settings.terrain_cell);
  std::vector<TerrainPlane> planes(shapes.size());
  for (std::size_t o = 0; o < shapes.size(); ++o)
    if (shapes[o].points > 0)
      planes[o] = terrain.planeAround(shapes[o], settings.terrain_margin,
                                      shapes[o].family() == kGround ? static_cast<int>(o) : -2);
  const std::vector<std::vector<double>> detrended = detrendedHeights(points, labels, planes);
  std::vector<ObjectClass> classes(shapes.size(), ObjectClass::Unclassified);
  for (std::size_t o = 0; o < shapes.size(); ++o) {
    const ObjectShape& s = shapes[o];
    if (s.points == 0)
      continue;
    const int family = s.family();
    if (family == kRough) {
      classes[o] = ObjectClass::Vegetation;
      continue;
    }
    // Heights along the terrain's slope; the ground family against the other ground only.
    const TerrainPlane& plane = planes[o];
    const std::vector<double> z = stats::quantiles(detrended[o], {0.05, 0.5, 0.95});
    const double low = z[0], middle = z[1], top = z[2], level = plane.level;
    if (family == kGround) {
      classes[o] = raisedAbove(s, middle, level, settings) ? ObjectClass::Building
                                                           : ObjectClass::Ground;
      continue;
    }
    if (standsUpright(s, low, middle, top, settings))
      classes[o] = ObjectClass::Pole;
    else
      classes[o] = family == kSurface ? surfaceClass(s, low, middle, top, level, settings)
                                      : linearClass(s, low - level, settings);
  }
  return classes;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
