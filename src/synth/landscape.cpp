#include <pcl_ls3d/synth/landscape.h>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {
namespace synth {

const char*
toString(LandscapeType type)
{
  switch (type) {
  case LandscapeType::URBAN:
    return "urban";
  case LandscapeType::MOUNTAIN:
    return "mountain";
  default:
    return "rolling";
  }
}

bool
LandscapeSettings::isValid(std::string* why) const
{
  auto fail = [why](const char* msg) {
    if (why)
      *why = msg;
    return false;
  };
  if (!landforms.isValid(why))
    return false;
  if (!(trees_per_hectare >= 0.0 && min_crown_radius > 0.0 && max_crown_radius >= min_crown_radius &&
        min_tree_height > 0.0 && max_tree_height >= min_tree_height))
    return fail("tree sizes must be positive with min <= max");
  if (!(penetration >= 0.0 && penetration <= 1.0))
    return fail("penetration must be in [0, 1]");
  if (!(road_spacing >= 0.0 && road_width > 0.0 && std::isfinite(road_heading)))
    return fail("road_spacing must be >= 0 and road_width > 0");
  if (road_spacing > 0.0 && !(road_width < road_spacing))
    return fail("road_width must be below road_spacing");
  return true;
}

/// Crowns with a uniform grid over their discs.
struct Landscape::Trees
{
  struct Crown
  {
    Eigen::Vector2d c;
    double r, centre_z, half_depth;  // ellipsoid centre height and vertical semi-axis
  };
  static constexpr double kCell = 10.0;
  std::vector<Crown> crowns;
  std::vector<std::vector<int>> cells;
  Eigen::Vector2d min = Eigen::Vector2d::Zero();
  int nx = 0, ny = 0;

  void
  index(const Eigen::AlignedBox2d& region)
  {
    min = region.min();
    nx = static_cast<int>(region.sizes().x() / kCell) + 1;
    ny = static_cast<int>(region.sizes().y() / kCell) + 1;
    cells.assign(static_cast<std::size_t>(nx * ny), {});
    for (int i = 0; i < static_cast<int>(crowns.size()); ++i) {
      const Crown& k = crowns[static_cast<std::size_t>(i)];
      const Eigen::Vector2d lo = (k.c - min).array() - k.r, hi = (k.c - min).array() + k.r;
      for (int y = std::max(0, static_cast<int>(lo.y() / kCell));
           y <= std::min(ny - 1, static_cast<int>(hi.y() / kCell)); ++y)
        for (int x = std::max(0, static_cast<int>(lo.x() / kCell));
             x <= std::min(nx - 1, static_cast<int>(hi.x() / kCell)); ++x)
          cells[static_cast<std::size_t>(y * nx + x)].push_back(i);
    }
  }

  // The crown whose disc holds (x, y), or nullptr.
  const Crown*
  find(double x, double y) const
  {
    const double fx = (x - min.x()) / kCell, fy = (y - min.y()) / kCell;
    if (crowns.empty() || fx < 0.0 || fy < 0.0 || fx >= nx || fy >= ny)
      return nullptr;
    for (int i : cells[static_cast<std::size_t>(static_cast<int>(fy) * nx + static_cast<int>(fx))]) {
      const Crown& k = crowns[static_cast<std::size_t>(i)];
      if ((k.c - Eigen::Vector2d(x, y)).squaredNorm() < k.r * k.r)
        return &k;
    }
    return nullptr;
  }
};

namespace {

// Buildings off the roads, roofs raised above the landforms' ground (eave kept above the
// highest ground of the footprint by as much as placeBuildings put it above the terrain).
std::vector<Building>
fitBuildings(std::vector<Building> in, const Landscape& scene, const Terrain& terrain)
{
  std::vector<Building> out;
  for (Building b : in) {
    if (scene.onRoad(b.centre.x(), b.centre.y(), b.radius() + 2.0))
      continue;
    double lift = 0.0;
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; j <= 4; ++j) {
        const Eigen::Vector2d uv((i / 4.0 - 0.5) * b.length, (j / 4.0 - 0.5) * b.width);
        const Eigen::Vector2d p = b.centre + Eigen::Rotation2Dd(b.heading) * uv;
        lift = std::max(lift, scene.groundHeight(p.x(), p.y()) - terrain.height(p.x(), p.y()));
      }
    b.eave_z += lift;
    out.push_back(b);
  }
  return out;
}

}  // namespace

Landscape::Landscape(const Terrain& terrain, const LandscapeSettings& settings, bool buildings,
                     const BuildingSettings& building_settings, const Eigen::AlignedBox2d& region,
                     std::uint32_t seed)
    : settings_(settings), ground_(terrain, settings.landforms, region, seed),
      trees_(std::make_unique<Trees>())
{
  std::vector<Building> placed;
  if (buildings)
    placed = placeBuildings(terrain, region, building_settings, seed);
  if (settings.type != LandscapeType::ROLLING)
    placed = fitBuildings(std::move(placed), *this, terrain);
  surface_ = std::make_shared<SurfaceModel>(terrain, BuildingSet(std::move(placed)));
  if (settings.type == LandscapeType::ROLLING)
    return;
  Random rng(seed, 0x7ee5u, 0u);
  const auto wanted =
      static_cast<std::size_t>(std::lround(settings.trees_per_hectare * region.volume() / 1e4));
  for (std::size_t attempt = 0; attempt < 3 * wanted && trees_->crowns.size() < wanted; ++attempt) {
    const Eigen::Vector2d c(rng.uniform(region.min().x(), region.max().x()),
                            rng.uniform(region.min().y(), region.max().y()));
    const double r = rng.uniform(settings.min_crown_radius, settings.max_crown_radius);
    const double h = rng.uniform(settings.min_tree_height, settings.max_tree_height);
    if (onRoad(c.x(), c.y(), r) || surface_->buildings().find(c.x(), c.y(), 2.0) >= 0)
      continue;
    const double half = 0.3 * h;
    trees_->crowns.push_back({c, r, groundHeight(c.x(), c.y()) + h - half, half});
  }
  trees_->index(region);
}

Landscape::~Landscape() = default;

std::size_t
Landscape::treeCount() const
{
  return trees_->crowns.size();
}

double
Landscape::groundHeight(double x, double y) const
{
  return ground_.height(x, y);
}

bool
Landscape::onRoad(double x, double y, double margin) const
{
  const double S = settings_.road_spacing;
  if (!(S > 0.0) || settings_.type == LandscapeType::ROLLING)
    return false;
  const Eigen::Vector2d r1(std::cos(settings_.road_heading), std::sin(settings_.road_heading));
  const double u = r1.x() * x + r1.y() * y, v = -r1.y() * x + r1.x() * y;
  const double du = std::abs(u - S * std::round(u / S)), dv = std::abs(v - S * std::round(v / S));
  return std::min(du, dv) <= 0.5 * settings_.road_width + margin;
}

Hit
Landscape::hit(double x, double y, Random& rng) const
{
  Hit h;
  int b = -1;
  if (settings_.type == LandscapeType::ROLLING) {
    h.z = surface_->height(x, y, &b);
  } else if (const Trees::Crown* k = trees_->find(x, y)) {
    if (rng.uniform(0.0, 1.0) >= settings_.penetration) {
      const double rho2 = (k->c - Eigen::Vector2d(x, y)).squaredNorm() / (k->r * k->r);
      h.z = k->centre_z + k->half_depth * std::sqrt(std::max(0.0, 1.0 - rho2)) - rng.uniform(0.0, 1.0);
      h.classification = 5;
      h.intensity_base = 80.0f;
      return h;
    }
    h.z = groundHeight(x, y);
    return h;
  } else {
    b = surface_->buildings().find(x, y);
    h.z = b >= 0 ? surface_->buildings().buildings()[static_cast<std::size_t>(b)].roofHeight(x, y)
                 : groundHeight(x, y);
    if (b < 0 && onRoad(x, y))
      h.intensity_base = 25.0f;
  }
  if (b >= 0) {
    h.classification = 6;
    h.intensity_base = 120.0f;
  }
  return h;
}

}  // namespace synth
}  // namespace pcl_ls3d
