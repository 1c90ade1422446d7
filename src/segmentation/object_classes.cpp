/// \file object_classes.cpp
/// \brief Classes of the assembled objects: kind votes, terrain height and plan size.

#include <pcl_ls3d/segmentation/object_classes.h>

#include <pcl_ls3d/common/voxel_index.h>
#include <pcl_ls3d/segmentation/ground_filter.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
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

/// What one object looks like: kind votes, z sample, plan moments and box along its axes.
struct ObjectShape
{
  std::size_t votes[kFamilies] = {0, 0, 0, 0};
  std::vector<float> z;
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

/// q-quantile of a sample (partially reorders it).
float
quantile(std::vector<float>& v, double q)
{
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

std::vector<ObjectShape>
objectShapes(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
             const std::vector<SegmentKind>& point_kind)
{
  const int n_objects = labels.empty() ? 0 : *std::max_element(labels.begin(), labels.end()) + 1;
  std::vector<ObjectShape> shapes(static_cast<std::size_t>(std::max(0, n_objects)));
  std::vector<char> seen(shapes.size(), 0);
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (labels[p] < 0)
      continue;
    ObjectShape& s = shapes[static_cast<std::size_t>(labels[p])];
    const Eigen::Vector2d xy = points[p].head<2>().cast<double>();
    if (!seen[static_cast<std::size_t>(labels[p])]) {
      seen[static_cast<std::size_t>(labels[p])] = 1;
      s.origin = xy;
    }
    ++s.votes[familyOf(point_kind[p])];
    s.z.push_back(points[p].z());
    const Eigen::Vector2d d = xy - s.origin;
    s.sum += d;
    s.sum_sq += d * d.transpose();
    s.box_lo = s.box_lo.cwiseMin(xy);
    s.box_hi = s.box_hi.cwiseMax(xy);
  }
  for (ObjectShape& s : shapes) {
    const double n = static_cast<double>(s.z.size());
    if (n < 2.0)
      continue;
    const Eigen::Matrix2d cov = s.sum_sq / n - (s.sum / n) * (s.sum / n).transpose();
    s.axis = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov).eigenvectors().col(1);
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (labels[p] < 0)
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
countLinearCover(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
                 double cell, std::vector<ObjectShape>& shapes)
{
  std::unordered_set<std::uint64_t> seen;
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (labels[p] < 0)
      continue;
    ObjectShape& s = shapes[static_cast<std::size_t>(labels[p])];
    if (s.family() != kLinear)
      continue;
    // Object and cell in one key; a collision only undercounts a cover.
    const auto x = static_cast<std::uint64_t>(voxelCoordinate(points[p].x(), cell)) & 0xfffffu;
    const auto y = static_cast<std::uint64_t>(voxelCoordinate(points[p].y(), cell)) & 0xfffffu;
    if (seen.insert(static_cast<std::uint64_t>(labels[p]) << 40 | x << 20 | y).second)
      ++s.cover;
  }
}

/// Median lowest ground point of the cells within the margin of an object's plan box; NaN
/// when none holds a ground point.
class TerrainLevels
{
public:
  TerrainLevels(const std::vector<Eigen::Vector3f>& points, const std::vector<char>& ground,
                double cell)
  {
    std::vector<Eigen::Vector3f> kept;
    for (std::size_t p = 0; p < points.size(); ++p)
      if (ground[p])
        kept.push_back(points[p]);
    if (!kept.empty())
      grid_ = std::make_unique<LowestPointGrid>(kept, cell);
  }

  float under(const ObjectShape& s, double margin) const
  {
    if (!grid_)
      return std::numeric_limits<float>::quiet_NaN();
    const Eigen::Vector2d lo = s.box_lo.array() - margin, hi = s.box_hi.array() + margin;
    const int first = grid_->cellOf(Eigen::Vector3f(float(lo.x()), float(lo.y()), 0.0f));
    const int last = grid_->cellOf(Eigen::Vector3f(float(hi.x()), float(hi.y()), 0.0f));
    std::vector<float> levels;
    for (int r = first / grid_->cols(); r <= last / grid_->cols(); ++r)
      for (int c = first % grid_->cols(); c <= last % grid_->cols(); ++c) {
        const float z = grid_->lowest()[static_cast<std::size_t>(r) * grid_->cols() + c];
        if (std::isfinite(z))
          levels.push_back(z);
      }
    return levels.empty() ? std::numeric_limits<float>::quiet_NaN() : quantile(levels, 0.5);
  }

private:
  std::unique_ptr<LowestPointGrid> grid_;
};

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

/// Lowest point per plan cell of the ground-family objects, and the object it belongs to: the
/// terrain that the other ground objects show around one of them.
class GroundCells
{
public:
  GroundCells(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
              const std::vector<ObjectShape>& shapes, double cell)
  : cell_(cell)
  {
    for (std::size_t p = 0; p < points.size(); ++p) {
      if (labels[p] < 0 || shapes[static_cast<std::size_t>(labels[p])].family() != kGround)
        continue;
      const auto key = keyOf(voxelCoordinate(points[p].x(), cell_),
                             voxelCoordinate(points[p].y(), cell_));
      const auto [it, fresh] = cells_.try_emplace(key, Lowest{points[p].z(), labels[p]});
      if (!fresh && points[p].z() < it->second.z)
        it->second = Lowest{points[p].z(), labels[p]};
    }
  }

  /// Median of the lowest points of other ground objects in the cells within \a margin of the
  /// plan box of \a object; NaN when there are none.
  float othersUnder(const ObjectShape& s, int object, double margin) const
  {
    const std::int64_t x0 = voxelCoordinate(s.box_lo.x() - margin, cell_);
    const std::int64_t x1 = voxelCoordinate(s.box_hi.x() + margin, cell_);
    const std::int64_t y0 = voxelCoordinate(s.box_lo.y() - margin, cell_);
    const std::int64_t y1 = voxelCoordinate(s.box_hi.y() + margin, cell_);
    std::vector<float> levels;
    const auto take = [&](const Lowest& l) {
      if (l.object != object)
        levels.push_back(l.z);
    };
    if (static_cast<double>(x1 - x0 + 1) * static_cast<double>(y1 - y0 + 1) >
        static_cast<double>(cells_.size())) {
      for (const auto& [key, lowest] : cells_) {
        const auto x = static_cast<std::int32_t>(key >> 32), y = static_cast<std::int32_t>(key);
        if (x >= x0 && x <= x1 && y >= y0 && y <= y1)
          take(lowest);
      }
    }
    else {
      for (std::int64_t x = x0; x <= x1; ++x)
        for (std::int64_t y = y0; y <= y1; ++y) {
          const auto it = cells_.find(keyOf(x, y));
          if (it != cells_.end())
            take(it->second);
        }
    }
    return levels.empty() ? std::numeric_limits<float>::quiet_NaN() : quantile(levels, 0.5);
  }

private:
  struct Lowest
  {
    float z;
    int object;
  };
  static std::uint64_t keyOf(std::int64_t x, std::int64_t y)
  {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) |
           static_cast<std::uint32_t>(y);
  }
  double cell_;
  std::unordered_map<std::uint64_t, Lowest> cells_;
};

ObjectClass
surfaceClass(const ObjectShape& s, double top, const ObjectClassSettings& c)
{
  const bool known = std::isfinite(top);
  if (known && top <= c.car_max_height && s.length() >= c.car_min_length &&
      s.length() <= c.car_max_length && s.width() >= c.car_min_width &&
      s.width() <= c.car_max_width)
    return ObjectClass::Car;
  if ((!known || top >= c.min_building_height) &&
      s.length() * s.width() >= c.min_building_area)
    return ObjectClass::Building;
  return ObjectClass::Unclassified;
}

/// A ground-like object standing clearly above the other ground around it is a roof that the
/// ground filter kept (wider than its largest window, or with little terrain around).
bool
raisedAbove(ObjectShape& s, float others, const ObjectClassSettings& c)
{
  return std::isfinite(others) && quantile(s.z, 0.5) - others >= c.min_building_height &&
         s.length() * s.width() >= c.min_building_area;
}

ObjectClass
linearClass(const ObjectShape& s, double low, const ObjectClassSettings& c)
{
  const double thin = c.max_wire_cover * s.length() / c.wire_cell;
  if (std::isfinite(low) && low >= c.min_wire_height && s.length() >= c.min_wire_length &&
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
  const TerrainLevels terrain(points, ground, settings.terrain_cell);
  const GroundCells ground_cells(points, labels, shapes, settings.terrain_cell);
  std::vector<ObjectClass> classes(shapes.size(), ObjectClass::Unclassified);
  for (std::size_t o = 0; o < shapes.size(); ++o) {
    ObjectShape& s = shapes[o];
    if (s.z.empty())
      continue;
    const int family = s.family();
    if (family == kRough) {
      classes[o] = ObjectClass::Vegetation;
      continue;
    }
    if (family == kGround) {
      classes[o] = raisedAbove(s, ground_cells.othersUnder(s, static_cast<int>(o),
                                                          settings.terrain_margin), settings)
                       ? ObjectClass::Building
                       : ObjectClass::Ground;
      continue;
    }
    const float level = terrain.under(s, settings.terrain_margin);
    const double low = quantile(s.z, 0.05), middle = quantile(s.z, 0.5),
                 top = quantile(s.z, 0.95);
    if (standsUpright(s, low, middle, top, settings))
      classes[o] = ObjectClass::Pole;
    else
      classes[o] = family == kSurface ? surfaceClass(s, top - level, settings)
                                      : linearClass(s, low - level, settings);
  }
  return classes;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
