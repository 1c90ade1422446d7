#include "sampling.h"

#include <pcl_ls3d/synth/strip_block.h>

#include <pcl/console/print.h>

#include <cmath>

namespace pcl_ls3d {
namespace synth {

bool
StripSettings::isValid(std::string* why) const
{
  auto fail = [why](const char* msg) {
    if (why)
      *why = msg;
    return false;
  };
  if (num_strips < 1 || num_strips > 65535)
    return fail("num_strips must be in [1, 65535]");
  if (!(strip_length > 0.0 && swath_width > 0.0 && density > 0.0 && speed > 0.0))
    return fail("strip_length, swath_width, density and speed must be positive");
  if (!(side_overlap >= 0.0 && side_overlap < 1.0))
    return fail("side_overlap must be in [0, 1)");
  if (!(noise_sigma >= 0.0 && shift_sigma >= 0.0 && angle_sigma >= 0.0 && scale_sigma >= 0.0))
    return fail("sigmas must be >= 0");
  if (!(relief >= 0.0 && wavelength > 0.0))
    return fail("relief must be >= 0 and wavelength > 0");
  if (!std::isfinite(heading) || !std::isfinite(start_time) || !std::isfinite(turn_time) ||
      !origin.allFinite())
    return fail("heading, times and origin must be finite");
  if (!transforms.empty() && static_cast<int>(transforms.size()) != num_strips)
    return fail("transforms must be empty or hold one transform per strip");
  for (const auto& t : transforms)
    if (!(t.m > 0.0) || !t.vector().allFinite())
      return fail("transforms must be finite with m > 0");
  if (static_cast<double>(first_source_id) + num_strips - 1 > 65535.0)
    return fail("point_source_id would exceed 65535");
  if (num_strips * strip_length * swath_width * density > 2e9)
    return fail("too many points (more than 2e9)");
  return true;
}

pcl::PointCloud<PointLiDAR>::Ptr
StripBlock::stripCloud(std::size_t s) const
{
  pcl::PointCloud<PointLiDAR>::Ptr out(new pcl::PointCloud<PointLiDAR>);
  if (!cloud || s >= strips.size())
    return out;
  const auto first = cloud->begin() + static_cast<std::ptrdiff_t>(strips[s].first_index);
  out->insert(out->end(), first, first + static_cast<std::ptrdiff_t>(strips[s].point_count));
  return out;
}

namespace {

/// Per-strip truths: explicit ones, or random errors drawn about each strip centre.
void
drawTruths(const StripSettings& s, std::vector<StripTruth>& strips)
{
  Random rng(s.seed, 0x57a1u, 0u);
  for (std::size_t i = 0; i < strips.size(); ++i) {
    StripTruth& st = strips[i];
    const Eigen::Vector3d& c = st.centre;
    // Draw first, so the sequence does not depend on fix_first.
    Vector7d p;
    p << rng.normal(0.0, s.shift_sigma), rng.normal(0.0, s.shift_sigma),
        rng.normal(0.0, s.shift_sigma), rng.normal(0.0, s.angle_sigma),
        rng.normal(0.0, s.angle_sigma), rng.normal(0.0, s.angle_sigma),
        1.0 + rng.normal(0.0, s.scale_sigma);
    st.fixed = i == 0 && s.fix_first;
    if (!s.transforms.empty()) {
      st.transform = s.transforms[i];
    }
    else if (st.fixed) {
      st.transform = SimilarityTransform();
    }
    else {
      // x' = c + t_c + mR(x − c)  ⇒  t = c + t_c − mRc.
      st.transform = SimilarityTransform(p);
      st.transform.t = c + p.head<3>() - p[SCALE] * (st.transform.rotation() * c);
    }
    const SimilarityTransform& T = st.transform;
    st.t_centre = T.t - c + T.m * (T.rotation() * c);
  }
}

}  // namespace

StripBlock
makeStripBlock(const StripSettings& s)
{
  StripBlock block;
  block.cloud.reset(new pcl::PointCloud<PointLiDAR>);
  block.origin = s.origin;
  std::string why;
  if (!s.isValid(&why)) {
    PCL_ERROR("[pcl_ls3d::synth::makeStripBlock] invalid settings: %s\n", why.c_str());
    return block;
  }
  const Eigen::Vector2d d(std::cos(s.heading), std::sin(s.heading));
  const Eigen::Vector2d a(-d.y(), d.x());
  block.direction = d;
  block.strip_spacing = s.swath_width * (1.0 - s.side_overlap);

  const std::size_t n_c =
      std::max<std::size_t>(1, std::lround(s.swath_width * std::sqrt(s.density)));
  const double dc = s.swath_width / static_cast<double>(n_c);
  const double da = 1.0 / (s.density * dc);
  const std::size_t n_lines = std::max<std::size_t>(1, std::lround(s.strip_length / da));
  const double strip_time = s.strip_length / s.speed + s.turn_time;

  block.strips.resize(static_cast<std::size_t>(s.num_strips));
  Eigen::AlignedBox2d region;
  for (int i = 0; i < s.num_strips; ++i) {
    StripTruth& st = block.strips[i];
    const Eigen::Vector2d c = (i - 0.5 * (s.num_strips - 1)) * block.strip_spacing * a;
    st.centre = Eigen::Vector3d(c.x(), c.y(), 0.0);
    st.point_source_id = static_cast<std::uint16_t>(s.first_source_id + i);
    const Eigen::Vector2d L = 0.5 * s.strip_length * d, W = 0.5 * s.swath_width * a;
    st.footprint = {c - L + W, c - L - W, c + L - W, c + L + W};
    for (const auto& corner : st.footprint)
      region.extend(corner);
    st.scan_lines = n_lines;
    st.points_per_line = n_c;
    st.point_count = n_lines * n_c;
    st.first_index = static_cast<std::size_t>(i) * st.point_count;
    st.start_time = s.start_time + i * strip_time;
    st.end_time = st.start_time + static_cast<double>(n_lines) * da / s.speed;
  }
  drawTruths(s, block.strips);

  Terrain terrain(s.seed, s.relief, s.wavelength);
  std::vector<Building> buildings;
  if (s.buildings)
    buildings = placeBuildings(terrain, region, s.building_settings, s.seed);
  auto surface = std::make_shared<SurfaceModel>(terrain, BuildingSet(std::move(buildings)));
  block.surface = surface;

  const std::size_t per_strip = n_lines * n_c;
  const std::size_t total = per_strip * block.strips.size();
  auto& cloud = *block.cloud;
  cloud.resize(total);
  cloud.width = static_cast<std::uint32_t>(total);
  cloud.height = 1;
  cloud.is_dense = true;
  std::vector<Eigen::Matrix4d> inverse;
  for (const auto& st : block.strips)
    inverse.push_back(st.transform.matrix().inverse());

  detail::forEachBlocked(total, s.seed, 0x5791u, [&](std::size_t idx, Random& rng) {
    const std::size_t strip = idx / per_strip, local = idx % per_strip;
    const std::size_t k = local / n_c, j = local % n_c;
    const double f = (static_cast<double>(j) + 0.5) / static_cast<double>(n_c);
    const bool reverse = s.pattern == ScanPattern::ZIGZAG && (k % 2 == 1);
    const double across = ((reverse ? 1.0 - f : f) - 0.5) * s.swath_width;
    const double along_pos = (static_cast<double>(k) + f) * da;
    const StripTruth& st = block.strips[strip];
    const Eigen::Vector2d xy =
        st.centre.head<2>() + (along_pos - 0.5 * s.strip_length) * d + across * a;
    int b = -1;
    const double z = surface->height(xy.x(), xy.y(), &b);
    const Eigen::Vector4d p(xy.x(), xy.y(), z, 1.0);
    const Eigen::Vector4d noisy = p + (Eigen::Vector4d() << rng.normal3(s.noise_sigma), 0.0).finished();
    PointLiDAR& q = cloud[idx];
    q = detail::makePoint((inverse[strip] * noisy).head<3>());
    q.classification = b >= 0 ? 6 : 2;
    q.intensity = static_cast<float>((b >= 0 ? 120.0 : 50.0) + rng.uniform(-10.0, 10.0));
    q.point_source_id = st.point_source_id;
    q.gps_time = st.start_time + along_pos / s.speed;
  });
  return block;
}

}  // namespace synth
}  // namespace pcl_ls3d
