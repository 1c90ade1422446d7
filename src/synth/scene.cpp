#include "sampling.h"
#include "scene_layout.h"

#include <pcl_ls3d/synth/scene.h>

#include <pcl/console/print.h>

#include <array>
#include <cmath>

namespace pcl_ls3d {
namespace synth {

const char*
toString(ObjectType t)
{
  static const std::array<const char*, 7> names{"building", "tree", "shrub", "car",
                                                "tower",    "wire", "ground"};
  return names[static_cast<int>(t)];
}

bool
SceneSettings::isValid(std::string* why) const
{
  auto fail = [why](const char* msg) {
    if (why)
      *why = msg;
    return false;
  };
  if (!(size_x > 0.0 && size_y > 0.0 && density > 0.0))
    return fail("size_x, size_y and density must be positive");
  if (!(noise_sigma >= 0.0 && relief >= 0.0 && wavelength > 0.0))
    return fail("noise_sigma, relief must be >= 0 and wavelength > 0");
  if (!(wall_density_ratio >= 0.0 && trees_per_hectare >= 0.0 && shrubs_per_hectare >= 0.0 &&
        cars_per_hectare >= 0.0))
    return fail("object densities must be >= 0");
  if (!(low_max > 0.0 && medium_max > low_max))
    return fail("need 0 < low_max < medium_max");
  if (power_line && (towers < 2 || wires < 1 || !(tower_height > 3.0) ||
                     !(wire_sag > 0.0 && wire_sag < 0.3) || !(line_spacing > 0.0)))
    return fail(
        "power line needs towers >= 2, wires >= 1, tower_height > 3, 0 < wire_sag < 0.3, line_spacing > 0");
  if (!origin.allFinite())
    return fail("origin must be finite");
  if (size_x * size_y * density > 5e8)
    return fail("too many points (more than 5e8 pulses)");
  return true;
}

std::map<int, std::size_t>
LabelledScene::classCounts() const
{
  std::map<int, std::size_t> counts;
  if (cloud)
    for (const auto& p : *cloud)
      ++counts[p.classification];
  return counts;
}

namespace {

/// Uniform grid over crown discs (crowns are small; 10 m cells).
class CrownGrid
{
public:
  CrownGrid(const std::vector<detail::Crown>& crowns, const Eigen::Vector2d& half)
      : crowns_(crowns), min_(-half), nx_(static_cast<int>(2 * half.x() / kCell) + 1),
        ny_(static_cast<int>(2 * half.y() / kCell) + 1), cells_(static_cast<std::size_t>(nx_) * ny_)
  {
    for (int i = 0; i < static_cast<int>(crowns.size()); ++i) {
      const auto& c = crowns[i];
      for (int iy = cell(c.c.y() - c.r, min_.y(), ny_); iy <= cell(c.c.y() + c.r, min_.y(), ny_); ++iy)
        for (int ix = cell(c.c.x() - c.r, min_.x(), nx_); ix <= cell(c.c.x() + c.r, min_.x(), nx_); ++ix)
          cells_[static_cast<std::size_t>(iy) * nx_ + ix].push_back(i);
    }
  }
  /// Crown whose disc contains (x, y), or −1.
  int
  find(double x, double y) const
  {
    for (int i : cells_[static_cast<std::size_t>(cell(y, min_.y(), ny_)) * nx_ + cell(x, min_.x(), nx_)])
      if ((crowns_[i].c - Eigen::Vector2d(x, y)).squaredNorm() < crowns_[i].r * crowns_[i].r)
        return i;
    return -1;
  }

private:
  static constexpr double kCell = 10.0;
  static int
  cell(double v, double lo, int n)
  {
    return std::max(0, std::min(n - 1, static_cast<int>((v - lo) / kCell)));
  }
  const std::vector<detail::Crown>& crowns_;
  Eigen::Vector2d min_;
  int nx_, ny_;
  std::vector<std::vector<int>> cells_;
};

struct Collected
{
  std::vector<PointLiDAR, Eigen::aligned_allocator<PointLiDAR>> points;
  std::vector<int> ids, planes;
  void
  add(const Eigen::Vector3d& p, std::uint8_t cls, int id, double time, int ret = 1, int nret = 1,
      int plane = -1)
  {
    planes.push_back(plane);
    PointLiDAR q = detail::makePoint(p);
    q.classification = cls;
    q.gps_time = time;
    q.return_number = static_cast<std::uint8_t>(ret);
    q.number_of_returns = static_cast<std::uint8_t>(nret);
    q.intensity = static_cast<float>(cls == 2 ? 50 : cls == 6 ? 120 : cls <= 5 ? 80 : 150);
    q.point_source_id = 1;
    points.push_back(q);
    ids.push_back(id);
  }
};

std::uint8_t
vegetationClass(double above, const SceneSettings& s)
{
  return above < s.low_max ? 3 : above < s.medium_max ? 4 : 5;
}

/// One pulse from above at (x, y): crown returns (+ ground), else roof, car or terrain.
void
samplePulse(double x, double y, double time, Random& rng, const SceneSettings& s,
            const detail::SceneLayout& layout, const SurfaceModel& surface, const BuildingSet& cars,
            const CrownGrid& crowns, Collected& out)
{
  const double sig = s.noise_sigma;
  const double ground = surface.terrain().height(x, y);
  const int ci = crowns.find(x, y);
  if (ci >= 0) {
    const auto& c = layout.crowns[ci];
    const double rho2 = (c.c - Eigen::Vector2d(x, y)).squaredNorm() / (c.r * c.r);
    const double h = std::sqrt(std::max(0.0, 1.0 - rho2)) * 0.5 * (c.top - c.base);
    const double mid = 0.5 * (c.top + c.base), top = mid + h, bottom = mid - h;
    // Returns: first in the upper crown; a second inside it (50 %); ground through a gap (50 %).
    std::array<double, 3> z;
    int n = 0;
    z[n++] = top - rng.uniform(0.0, 0.25) * (top - bottom);
    if (rng.uniform() < 0.5)
      z[n++] = rng.uniform(bottom, z[0]);
    const bool to_ground = rng.uniform() < 0.5 && bottom > ground + 0.3;
    const int total = n + (to_ground ? 1 : 0);
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d p = Eigen::Vector3d(x, y, z[k]) + rng.normal3(sig);
      out.add(p, vegetationClass(p.z() - surface.terrain().height(p.x(), p.y()), s), c.object, time, k + 1,
              total);
    }
    if (to_ground)
      out.add(Eigen::Vector3d(x, y, ground) + rng.normal3(sig), 2, layout.ground_object, time, total, total);
    return;
  }
  int b = -1;
  const double z = surface.height(x, y, &b);
  if (b >= 0) {
    const int plane = layout.first_plane[b] + layout.buildings[b].roofPlane(x, y);
    out.add(Eigen::Vector3d(x, y, z) + rng.normal3(sig), 6, layout.building_object[b], time, 1, 1, plane);
    return;
  }
  const int car = cars.find(x, y);
  if (car >= 0) {
    out.add(Eigen::Vector3d(x, y, cars.buildings()[car].eave_z) + rng.normal3(sig), s.car_class,
            layout.car_object[car], time);
    return;
  }
  out.add(Eigen::Vector3d(x, y, ground) + rng.normal3(sig), 2, layout.ground_object, time);
}

/// Sparse wall points: uniform on each wall face between terrain and roof edge.
void
sampleWalls(const SceneSettings& s, const detail::SceneLayout& layout, const Terrain& terrain, Random& rng,
            double time, Collected& out)
{
  for (std::size_t i = 0; i < layout.buildings.size(); ++i) {
    const Building& b = layout.buildings[i];
    const double c = std::cos(b.heading), sn = std::sin(b.heading);
    const std::array<Eigen::Vector2d, 4> uv{
        Eigen::Vector2d(-0.5 * b.length, -0.5 * b.width), Eigen::Vector2d(0.5 * b.length, -0.5 * b.width),
        Eigen::Vector2d(0.5 * b.length, 0.5 * b.width), Eigen::Vector2d(-0.5 * b.length, 0.5 * b.width)};
    for (int e = 0; e < 4; ++e) {
      const Eigen::Vector2d a = uv[e], d = uv[(e + 1) % 4] - uv[e];
      // Gable end walls (odd edges, across the ridge) rise to the ridge: half of it on average.
      const double gable = b.roof == RoofType::GABLE ? 0.5 * b.ridge_rise * (e % 2) : 0.0;
      const double mean_h = b.eave_z + gable - terrain.height(b.centre.x(), b.centre.y());
      const auto n = static_cast<std::size_t>(
          std::lround(s.wall_density_ratio * s.density * d.norm() * std::max(0.0, mean_h)));
      for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Vector2d l = a + rng.uniform() * d;
        const double x = b.centre.x() + c * l.x() - sn * l.y();
        const double y = b.centre.y() + sn * l.x() + c * l.y();
        const double z = rng.uniform(terrain.height(x, y), b.roofHeight(x, y));
        out.add(Eigen::Vector3d(x, y, z) + rng.normal3(s.noise_sigma), 6, layout.building_object[i], time);
      }
    }
  }
}

/// Points along the towers' and wires' members, from one sequential stream.
void
sampleMembers(const SceneSettings& s, const detail::SceneLayout& layout, Random& rng, double time,
              Collected& out)
{
  for (const auto& m : layout.members) {
    const double length = (m.b - m.a).norm();
    const auto n = static_cast<std::size_t>(std::ceil(length / s.line_spacing));
    const std::uint8_t cls = layout.objects[m.object].classification;
    for (std::size_t k = 0; k < n; ++k) {
      const double u = (static_cast<double>(k) + rng.uniform()) / static_cast<double>(n);
      out.add(detail::segmentPoint(m, u) + rng.normal3(s.noise_sigma), cls, m.object, time);
    }
  }
}

/// The blocks' points and labels concatenated in order, with the point count per object and
/// roof plane.
void
assembleScene(const std::vector<Collected>& blocks, const detail::SceneLayout& layout, LabelledScene& scene)
{
  scene.objects = layout.objects;
  scene.planes = layout.planes;
  for (const auto& b : blocks) {
    scene.cloud->insert(scene.cloud->end(), b.points.begin(), b.points.end());
    scene.object_id.insert(scene.object_id.end(), b.ids.begin(), b.ids.end());
    scene.plane_id.insert(scene.plane_id.end(), b.planes.begin(), b.planes.end());
  }
  for (int id : scene.object_id)
    if (id >= 0)
      ++scene.objects[id].point_count;
  for (int id : scene.plane_id)
    if (id >= 0)
      ++scene.planes[static_cast<std::size_t>(id)].point_count;
  scene.cloud->width = static_cast<std::uint32_t>(scene.cloud->size());
  scene.cloud->height = 1;
  scene.cloud->is_dense = true;
}

}  // namespace

LabelledScene
makeScene(const SceneSettings& s)
{
  LabelledScene scene;
  scene.cloud.reset(new pcl::PointCloud<PointLiDAR>);
  scene.origin = s.origin;
  std::string why;
  if (!s.isValid(&why)) {
    PCL_ERROR("[pcl_ls3d::synth::makeScene] invalid settings: %s\n", why.c_str());
    return scene;
  }
  const Terrain terrain(s.seed, s.relief, s.wavelength);
  detail::SceneLayout layout = detail::layoutScene(s, terrain);
  auto surface = std::make_shared<SurfaceModel>(terrain, BuildingSet(layout.buildings));
  scene.surface = surface;
  const BuildingSet cars(layout.cars, 10.0);
  const Eigen::Vector2d half(0.5 * s.size_x, 0.5 * s.size_y);
  const CrownGrid crowns(layout.crowns, half);

  // Pulses, in blocks with their own streams (thread-count independent), then concatenated.
  const auto pulses = static_cast<std::size_t>(std::lround(s.size_x * s.size_y * s.density));
  const std::size_t nblocks = (pulses + detail::kBlock - 1) / detail::kBlock;
  std::vector<Collected> blocks(nblocks + 1);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t b = 0; b < static_cast<std::int64_t>(nblocks); ++b) {
    Random rng(s.seed, 0x9c3u, static_cast<std::uint32_t>(b));
    const std::size_t end = std::min(pulses, static_cast<std::size_t>(b + 1) * detail::kBlock);
    for (std::size_t i = static_cast<std::size_t>(b) * detail::kBlock; i < end; ++i) {
      const double x = rng.uniform(-half.x(), half.x()), y = rng.uniform(-half.y(), half.y());
      samplePulse(x, y, 1e-5 * static_cast<double>(i), rng, s, layout, *surface, cars, crowns, blocks[b]);
    }
  }
  // Walls, towers and wires: one sequential stream.
  Random rng(s.seed, 0x3a11u, 0u);
  Collected& extra = blocks.back();
  const double t_extra = 1e-5 * static_cast<double>(pulses) + 1.0;
  sampleWalls(s, layout, terrain, rng, t_extra, extra);
  sampleMembers(s, layout, rng, t_extra, extra);
  assembleScene(blocks, layout, scene);
  return scene;
}

}  // namespace synth
}  // namespace pcl_ls3d
