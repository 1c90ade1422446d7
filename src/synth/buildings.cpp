#include <pcl_ls3d/synth/buildings.h>
#include <pcl_ls3d/synth/random.h>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {
namespace synth {

Eigen::Vector2d
Building::toLocal(double x, double y) const
{
  const double c = std::cos(heading), s = std::sin(heading);
  const double dx = x - centre.x(), dy = y - centre.y();
  return {c * dx + s * dy, -s * dx + c * dy};
}

bool
Building::contains(double x, double y, double margin) const
{
  const Eigen::Vector2d uv = toLocal(x, y);
  return std::abs(uv.x()) <= 0.5 * length + margin && std::abs(uv.y()) <= 0.5 * width + margin;
}

int
roofPlaneCount(RoofType roof)
{
  return roof == RoofType::FLAT ? 1 : roof == RoofType::GABLE ? 2 : 4;
}

double
Building::roofHeight(double x, double y) const
{
  if (roof == RoofType::FLAT)
    return eave_z;
  const Eigen::Vector2d uv = toLocal(x, y);
  double to_eave = 0.5 * width - std::abs(uv.y());
  if (roof == RoofType::HIP)
    to_eave = std::min(to_eave, 0.5 * length - std::abs(uv.x()));
  return eave_z + ridge_rise * std::max(0.0, to_eave / (0.5 * width));
}

int
Building::roofPlane(double x, double y) const
{
  if (roof == RoofType::FLAT)
    return 0;
  const Eigen::Vector2d uv = toLocal(x, y);
  if (roof == RoofType::HIP && 0.5 * length - std::abs(uv.x()) < 0.5 * width - std::abs(uv.y()))
    return uv.x() >= 0.0 ? 2 : 3;
  return uv.y() >= 0.0 ? 0 : 1;
}

double
Building::radius() const
{
  return 0.5 * std::hypot(length, width);
}

BuildingSet::BuildingSet(std::vector<Building> buildings, double cell)
    : buildings_(std::move(buildings)), cell_(cell)
{
  if (buildings_.empty())
    return;
  Eigen::AlignedBox2d box;
  for (const auto& b : buildings_) {
    const Eigen::Vector2d r = Eigen::Vector2d::Constant(b.radius() + max_margin_);
    box.extend(b.centre - r);
    box.extend(b.centre + r);
  }
  min_ = box.min();
  nx_ = static_cast<int>(std::ceil(box.sizes().x() / cell_)) + 1;
  ny_ = static_cast<int>(std::ceil(box.sizes().y() / cell_)) + 1;
  cells_.assign(static_cast<std::size_t>(nx_) * ny_, {});
  for (int i = 0; i < static_cast<int>(buildings_.size()); ++i) {
    const Building& b = buildings_[i];
    const double r = b.radius() + max_margin_;
    const int x0 = static_cast<int>((b.centre.x() - r - min_.x()) / cell_);
    const int x1 = static_cast<int>((b.centre.x() + r - min_.x()) / cell_);
    const int y0 = static_cast<int>((b.centre.y() - r - min_.y()) / cell_);
    const int y1 = static_cast<int>((b.centre.y() + r - min_.y()) / cell_);
    for (int iy = std::max(0, y0); iy <= std::min(ny_ - 1, y1); ++iy)
      for (int ix = std::max(0, x0); ix <= std::min(nx_ - 1, x1); ++ix)
        cells_[static_cast<std::size_t>(iy) * nx_ + ix].push_back(i);
  }
}

int
BuildingSet::find(double x, double y, double margin) const
{
  if (cells_.empty())
    return -1;
  const double fx = (x - min_.x()) / cell_, fy = (y - min_.y()) / cell_;
  if (fx < 0.0 || fy < 0.0 || fx >= nx_ || fy >= ny_)
    return -1;
  const auto& cell = cells_[static_cast<std::size_t>(fy) * nx_ + static_cast<std::size_t>(fx)];
  if (margin > max_margin_) {  // the grid only covers max_margin_: fall back to a scan
    for (int i = 0; i < static_cast<int>(buildings_.size()); ++i)
      if (buildings_[i].contains(x, y, margin))
        return i;
    return -1;
  }
  for (int i : cell)
    if (buildings_[i].contains(x, y, margin))
      return i;
  return -1;
}

std::vector<Building>
placeBuildings(const Terrain& terrain, const Eigen::AlignedBox2d& region, const BuildingSettings& s,
               std::uint32_t seed)
{
  std::vector<Building> out;
  if (region.isEmpty() || s.per_hectare <= 0.0)
    return out;
  Random rng(seed, 0xb11d1u, 0u);
  const double area = region.volume();
  const std::size_t wanted = static_cast<std::size_t>(std::lround(s.per_hectare * area / 1e4));
  constexpr double kPi = 3.14159265358979323846;
  for (std::size_t attempt = 0; attempt < 50 * wanted && out.size() < wanted; ++attempt) {
    Building b;
    b.length = rng.uniform(s.min_length, s.max_length);
    b.width = std::min(b.length, rng.uniform(s.min_width, s.max_width));
    b.heading = rng.uniform(0.0, kPi);
    const double r = b.radius();
    b.centre = {rng.uniform(region.min().x() + r, region.max().x() - r),
                rng.uniform(region.min().y() + r, region.max().y() - r)};
    const double kind = rng.uniform();  // one draw whatever the mix: same layouts as before hips
    b.roof = kind < s.gable_fraction                    ? RoofType::GABLE
             : kind < s.gable_fraction + s.hip_fraction ? RoofType::HIP
                                                        : RoofType::FLAT;
    const double eave = rng.uniform(s.min_eave, s.max_eave);
    const double rise = rng.uniform(s.min_rise, s.max_rise);
    if (2.0 * r > region.sizes().minCoeff())
      continue;
    bool free = true;
    for (const auto& o : out)
      free = free && (o.centre - b.centre).norm() > o.radius() + r + s.gap;
    if (!free)
      continue;
    // Highest terrain under the footprint (5×5 samples), so the roof clears the ground.
    double top = -1e300;
    for (int i = -2; i <= 2; ++i)
      for (int j = -2; j <= 2; ++j) {
        const double u = 0.25 * i * b.length, v = 0.25 * j * b.width;
        const double c = std::cos(b.heading), sn = std::sin(b.heading);
        top = std::max(top, terrain.height(b.centre.x() + c * u - sn * v, b.centre.y() + sn * u + c * v));
      }
    b.eave_z = top + eave;
    b.ridge_rise = b.roof == RoofType::FLAT ? 0.0 : rise;
    out.push_back(b);
  }
  return out;
}

double
SurfaceModel::height(double x, double y, int* building) const
{
  const int i = buildings_.find(x, y);
  if (building)
    *building = i;
  return i >= 0 ? buildings_.buildings()[i].roofHeight(x, y) : terrain_.height(x, y);
}

}  // namespace synth
}  // namespace pcl_ls3d
