#include "scene_layout.h"

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {
namespace synth {
namespace detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Catenary parameter a with a·(cosh(L/2a) − 1) = sag (bisection; sag < L/2 always here).
double
catenaryParameter(double span, double sag)
{
  double lo = 1e-3 * span, hi = 1e6 * span;
  for (int i = 0; i < 200; ++i) {
    const double a = std::sqrt(lo * hi);
    (a * (std::cosh(0.5 * span / a) - 1.0) > sag ? lo : hi) = a;
  }
  return std::sqrt(lo * hi);
}

struct Corridor
{
  Eigen::Vector2d p, d;
  double half_length = 0.0, half_width = 0.0;
  bool active = false;
  bool
  hits(const Eigen::Vector2d& x, double r) const
  {
    if (!active)
      return false;
    const Eigen::Vector2d v = x - p;
    const double along = v.dot(d), across = std::abs(v.x() * d.y() - v.y() * d.x());
    return across < half_width + r && std::abs(along) < half_length + r;
  }
};

void
addPowerLine(const SceneSettings& s, const Terrain& terrain, Random& rng, const Corridor& cor,
             SceneLayout& out)
{
  const Eigen::Vector2d d = cor.d, n(-d.y(), d.x());
  const double wire_sep = 4.0;
  std::vector<std::vector<Eigen::Vector3d>> attach(static_cast<std::size_t>(s.towers));
  for (int i = 0; i < s.towers; ++i) {
    const double along = s.towers == 1 ? 0.0 : -cor.half_length + 2.0 * cor.half_length * i / (s.towers - 1);
    const Eigen::Vector2d c = cor.p + along * d;
    const double g = terrain.height(c.x(), c.y());
    const int id = static_cast<int>(out.objects.size());
    SceneObject o;
    o.id = id;
    o.type = ObjectType::TOWER;
    o.classification = 15;
    o.position = {c.x(), c.y(), g};
    o.size = {6.0, 6.0, s.tower_height};
    o.heading = std::atan2(d.y(), d.x());
    out.objects.push_back(o);
    // Tapering square lattice: 4 legs, a horizontal ring every 5 m, a cross arm at the top.
    auto corner = [&](int k, double z) {
      const double hw = 3.0 - 2.25 * z / s.tower_height;  // 3 m at the base, 0.75 m at the top
      const double sx = (k == 0 || k == 3) ? -1.0 : 1.0, sy = k < 2 ? -1.0 : 1.0;
      const Eigen::Vector2d xy = c + sx * hw * d + sy * hw * n;
      return Eigen::Vector3d(xy.x(), xy.y(), g + z);
    };
    for (int k = 0; k < 4; ++k)
      out.members.push_back({corner(k, 0.0), corner(k, s.tower_height), 0.0, id});
    for (double z = 5.0; z <= s.tower_height; z += 5.0)
      for (int k = 0; k < 4; ++k)
        out.members.push_back({corner(k, z), corner((k + 1) % 4, z), 0.0, id});
    const double arm_z = g + s.tower_height - 2.0;
    const double arm = 0.5 * (s.wires - 1) * wire_sep + 1.0;
    const Eigen::Vector2d a0 = c - arm * n, a1 = c + arm * n;
    out.members.push_back({{a0.x(), a0.y(), arm_z}, {a1.x(), a1.y(), arm_z}, 0.0, id});
    for (int w = 0; w < s.wires; ++w) {
      const Eigen::Vector2d xy = c + (w - 0.5 * (s.wires - 1)) * wire_sep * n;
      attach[i].emplace_back(xy.x(), xy.y(), arm_z - 0.5);  // insulators hang 0.5 m
    }
  }
  for (int i = 0; i + 1 < s.towers; ++i)
    for (int w = 0; w < s.wires; ++w) {
      const Eigen::Vector3d a = attach[i][w], b = attach[i + 1][w];
      const double span = (b - a).head<2>().norm();
      SceneObject o;
      o.id = static_cast<int>(out.objects.size());
      o.type = ObjectType::WIRE;
      o.classification = 14;
      o.position = a;
      o.size = {span, 0.03, s.wire_sag * span};
      o.heading = std::atan2(d.y(), d.x());
      out.objects.push_back(o);
      out.members.push_back({a, b, catenaryParameter(span, s.wire_sag * span), o.id});
    }
}

/// The power-line corridor: a random direction and centre; its towers stay inside the scene.
Corridor
makeCorridor(const SceneSettings& s, const Eigen::Vector2d& half, Random& rng)
{
  Corridor cor;
  cor.active = s.power_line && s.towers >= 1;
  const double theta = rng.uniform(0.0, kPi);
  cor.d = {std::cos(theta), std::sin(theta)};
  cor.p = {rng.uniform(-0.1, 0.1) * s.size_x, rng.uniform(-0.1, 0.1) * s.size_y};
  // Half length limited by the box along d.
  const double tx =
      std::abs(cor.d.x()) > 1e-9 ? (half.x() - std::abs(cor.p.x()) - 5.0) / std::abs(cor.d.x()) : 1e300;
  const double ty =
      std::abs(cor.d.y()) > 1e-9 ? (half.y() - std::abs(cor.p.y()) - 5.0) / std::abs(cor.d.y()) : 1e300;
  cor.half_length = std::max(0.0, 0.9 * std::min(tx, ty));
  cor.half_width = 0.5 * (s.wires - 1) * 4.0 + 8.0;
  return cor;
}

/// Places objects one after another on free ground: each takes a circle that no later object
/// and the power-line corridor may overlap.
class ObjectPlacer
{
public:
  ObjectPlacer(const SceneSettings& s, const Terrain& terrain, Random& rng, const Corridor& corridor,
               SceneLayout& out)
      : s_(s), terrain_(terrain), rng_(rng), corridor_(corridor), out_(out),
        half_(0.5 * s.size_x, 0.5 * s.size_y), region_(-half_, half_), area_ha_(s.size_x * s.size_y / 1e4)
  {}

  int
  add(ObjectType type, std::uint8_t cls, const Eigen::Vector3d& pos, const Eigen::Vector3d& size,
      double heading)
  {
    SceneObject o;
    o.id = static_cast<int>(out_.objects.size());
    o.type = type;
    o.classification = cls;
    o.position = pos;
    o.size = size;
    o.heading = heading;
    out_.objects.push_back(o);
    return o.id;
  }

  /// The buildings of placeBuildings() that find free ground, with their roof planes.
  void
  buildings()
  {
    for (const Building& b : placeBuildings(terrain_, region_, s_.building_settings, s_.seed)) {
      if (!take(b.centre, b.radius() + 1.0))
        continue;
      const double g = terrain_.height(b.centre.x(), b.centre.y());
      out_.building_object.push_back(add(ObjectType::BUILDING, 6, {b.centre.x(), b.centre.y(), g},
                                         {b.length, b.width, b.eave_z + b.ridge_rise - g}, b.heading));
      out_.buildings.push_back(b);
      out_.first_plane.push_back(static_cast<int>(out_.planes.size()));
      for (int k = 0; k < roofPlaneCount(b.roof); ++k)
        out_.planes.push_back({out_.building_object.back(), b.roof, k, 0});
    }
  }

  /// Tree crowns (class 5) or shrubs (class 4 below medium_max deep, else 5), per hectare.
  void
  crowns(double per_ha, bool shrub)
  {
    const auto wanted = static_cast<std::size_t>(std::lround(per_ha * area_ha_));
    std::size_t placed = 0;
    for (std::size_t k = 0; k < 30 * wanted && placed < wanted; ++k) {
      Crown c;
      c.c = {rng_.uniform(-half_.x(), half_.x()), rng_.uniform(-half_.y(), half_.y())};
      c.r = shrub ? rng_.uniform(0.5, 1.5) : rng_.uniform(2.0, 5.0);
      const double base = shrub ? 0.0 : rng_.uniform(2.0, 5.0);
      const double depth = shrub ? rng_.uniform(0.4, 1.8) : rng_.uniform(4.0, 9.0);
      if (!take(c.c, c.r + 0.5))
        continue;
      c.ground = terrain_.height(c.c.x(), c.c.y());
      c.base = c.ground + base;
      c.top = c.base + depth;
      const std::uint8_t cls = shrub ? (depth < s_.medium_max ? 4 : 5) : 5;
      c.object = add(shrub ? ObjectType::SHRUB : ObjectType::TREE, cls, {c.c.x(), c.c.y(), c.ground},
                     {2 * c.r, 2 * c.r, c.top - c.ground}, 0.0);
      out_.crowns.push_back(c);
      ++placed;
    }
  }

  /// Car-sized boxes standing on the highest terrain under their corners, per hectare.
  void
  cars()
  {
    const auto wanted = static_cast<std::size_t>(std::lround(s_.cars_per_hectare * area_ha_));
    for (std::size_t k = 0, placed = 0; k < 30 * wanted && placed < wanted; ++k) {
      Building car;
      car.length = rng_.uniform(4.0, 5.0);
      car.width = rng_.uniform(1.7, 2.0);
      car.heading = rng_.uniform(0.0, kPi);
      car.centre = {rng_.uniform(-half_.x(), half_.x()), rng_.uniform(-half_.y(), half_.y())};
      if (!take(car.centre, car.radius() + 0.5))
        continue;
      car.eave_z = highestTerrainUnder(car) + rng_.uniform(1.4, 1.8);
      const double g = terrain_.height(car.centre.x(), car.centre.y());
      out_.car_object.push_back(add(ObjectType::CAR, s_.car_class, {car.centre.x(), car.centre.y(), g},
                                    {car.length, car.width, car.eave_z - g}, car.heading));
      out_.cars.push_back(car);
      ++placed;
    }
  }

private:
  /// Takes the circle if it is free (inside the scene, off the corridor and every taken one).
  bool
  take(const Eigen::Vector2d& c, double r)
  {
    if (corridor_.hits(c, r))
      return false;
    for (const auto& t : taken_)
      if ((t.first - c).norm() < t.second + r)
        return false;
    if (!(region_.contains(c) && std::abs(c.x()) + r < half_.x() && std::abs(c.y()) + r < half_.y()))
      return false;
    taken_.emplace_back(c, r);
    return true;
  }

  double
  highestTerrainUnder(const Building& box) const
  {
    double top = -1e300;
    const double c = std::cos(box.heading), sn = std::sin(box.heading);
    for (int i = -1; i <= 1; i += 2)
      for (int j = -1; j <= 1; j += 2) {
        const double u = 0.5 * i * box.length, v = 0.5 * j * box.width;
        top =
            std::max(top, terrain_.height(box.centre.x() + c * u - sn * v, box.centre.y() + sn * u + c * v));
      }
    return top;
  }

  const SceneSettings& s_;
  const Terrain& terrain_;
  Random& rng_;
  const Corridor& corridor_;
  SceneLayout& out_;
  Eigen::Vector2d half_;
  Eigen::AlignedBox2d region_;
  double area_ha_;
  std::vector<std::pair<Eigen::Vector2d, double>> taken_;  // occupied circles
};

}  // namespace

Eigen::Vector3d
segmentPoint(const Segment& seg, double u)
{
  Eigen::Vector3d p = seg.a + u * (seg.b - seg.a);
  if (seg.catenary_a > 0.0) {
    const double L = (seg.b - seg.a).head<2>().norm(), a = seg.catenary_a;
    p.z() += a * (std::cosh((u - 0.5) * L / a) - std::cosh(0.5 * L / a));
  }
  return p;
}

SceneLayout
layoutScene(const SceneSettings& s, const Terrain& terrain)
{
  SceneLayout out;
  Random rng(s.seed, 0x5ce7eu, 0u);
  const Corridor corridor = makeCorridor(s, Eigen::Vector2d(0.5 * s.size_x, 0.5 * s.size_y), rng);
  ObjectPlacer placer(s, terrain, rng, corridor, out);
  if (s.buildings)
    placer.buildings();
  placer.crowns(s.trees_per_hectare, false);
  placer.crowns(s.shrubs_per_hectare, true);
  placer.cars();
  if (corridor.active)
    addPowerLine(s, terrain, rng, corridor, out);
  out.ground_object =
      placer.add(ObjectType::GROUND, 2, {0.0, 0.0, terrain.height(0.0, 0.0)}, {s.size_x, s.size_y, 0.0}, 0.0);
  return out;
}

}  // namespace detail
}  // namespace synth
}  // namespace pcl_ls3d
