#include "sampling.h"

#include <pcl_ls3d/synth/strip_block.h>

#include <pcl/console/print.h>

#include <algorithm>
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
  if (num_strips < 1 || cross_strips < 0 || num_strips + cross_strips > 65535)
    return fail("num_strips must be >= 1, cross_strips >= 0, together at most 65535");
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
  if (!transforms.empty() && static_cast<int>(transforms.size()) != totalStrips())
    return fail("transforms must be empty or hold one transform per strip");
  if (!errors.empty() && static_cast<int>(errors.size()) != totalStrips())
    return fail("errors must be empty or hold one error per strip");
  for (const auto& e : errors)
    if (!(e[SCALE] > 0.0) || !e.allFinite())
      return fail("errors must be finite with m > 0");
  if (!landscape.isValid(why))
    return false;
  for (const auto& t : transforms)
    if (!(t.m > 0.0) || !t.vector().allFinite())
      return fail("transforms must be finite with m > 0");
  if (static_cast<double>(first_source_id) + totalStrips() - 1 > 65535.0)
    return fail("point_source_id would exceed 65535");
  const double across = (num_strips - 1) * swath_width * (1.0 - side_overlap) + swath_width;
  if ((num_strips * strip_length + cross_strips * across) * swath_width * density > 2e9)
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
    p << rng.normal(0.0, s.shift_sigma), rng.normal(0.0, s.shift_sigma), rng.normal(0.0, s.shift_sigma),
        rng.normal(0.0, s.angle_sigma), rng.normal(0.0, s.angle_sigma), rng.normal(0.0, s.angle_sigma),
        1.0 + rng.normal(0.0, s.scale_sigma);
    if (!s.errors.empty())
      p = s.errors[i];
    st.fixed = i == 0 && s.fix_first;
    if (!s.transforms.empty()) {
      st.transform = s.transforms[i];
    } else if (st.fixed) {
      st.transform = SimilarityTransform();
    } else {
      // x' = c + t_c + mR(x − c)  ⇒  t = c + t_c − mRc.
      st.transform = SimilarityTransform(p);
      st.transform.t = c + p.head<3>() - p[SCALE] * (st.transform.rotation() * c);
    }
    const SimilarityTransform& T = st.transform;
    st.t_centre = T.t - c + T.m * (T.rotation() * c);
  }
}

/// Per scan line of each strip, its offset (u across, v along) in [0, 1) of a point spacing;
/// ½ is the regular lattice.
std::vector<std::vector<Eigen::Vector2d>>
drawLinePhases(const StripSettings& s, const std::vector<StripTruth>& strips)
{
  std::vector<std::vector<Eigen::Vector2d>> phase(strips.size());
  for (std::size_t i = 0; i < strips.size(); ++i) {
    phase[i].assign(strips[i].scan_lines, Eigen::Vector2d::Constant(0.5));
    if (!s.line_phase)
      continue;
    Random rng(s.seed, 0x9a5eu, static_cast<std::uint32_t>(i));
    for (auto& p : phase[i]) {
      const double u = rng.uniform(0.0, 1.0);  // drawn first: argument order is unspecified
      p = Eigen::Vector2d(u, rng.uniform(0.0, 1.0));
    }
  }
  return phase;
}

}  // namespace

namespace {

/// One flight line: centre, direction, length and scan geometry.
struct FlightLine
{
  Eigen::Vector2d c, d, a;  // centre, along, across
  double length = 0.0;
  std::size_t lines = 0;
};

/// The parallel strips, then the cross strips, with their truths' geometry filled in.
std::vector<FlightLine>
layOut(const StripSettings& s, StripBlock& block, double da, std::size_t n_c, Eigen::AlignedBox2d& region)
{
  const Eigen::Vector2d d = block.direction, a(-d.y(), d.x());
  const double across = (s.num_strips - 1) * block.strip_spacing + s.swath_width;
  std::vector<FlightLine> lines;
  for (int i = 0; i < s.num_strips; ++i)
    lines.push_back({(i - 0.5 * (s.num_strips - 1)) * block.strip_spacing * a, d, a, s.strip_length, 0});
  for (int k = 0; k < s.cross_strips; ++k)
    lines.push_back({((k + 0.5) / s.cross_strips - 0.5) * s.strip_length * d, a, -d, across, 0});
  block.strips.resize(lines.size());
  double t = s.start_time;
  std::size_t first = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    FlightLine& f = lines[i];
    f.lines = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(f.length / da)));
    StripTruth& st = block.strips[i];
    st.cross = static_cast<int>(i) >= s.num_strips;
    st.centre = Eigen::Vector3d(f.c.x(), f.c.y(), 0.0);
    st.point_source_id = static_cast<std::uint16_t>(s.first_source_id + i);
    const Eigen::Vector2d L = 0.5 * f.length * f.d, W = 0.5 * s.swath_width * f.a;
    st.footprint = {f.c - L + W, f.c - L - W, f.c + L - W, f.c + L + W};
    for (const auto& corner : st.footprint)
      region.extend(corner);
    st.scan_lines = f.lines;
    st.points_per_line = n_c;
    st.point_count = f.lines * n_c;
    st.first_index = first;
    first += st.point_count;
    st.start_time = t;
    st.end_time = t + static_cast<double>(f.lines) * da / s.speed;
    t += f.length / s.speed + s.turn_time;
  }
  return lines;
}

/// Samples the strips' points: each point's scan position on its flight line, its hit on the
/// landscape with noise, in its strip's distorted frame.
struct StripSampler
{
  const StripSettings& s;
  const StripBlock& block;
  const std::vector<FlightLine>& lines;
  const std::vector<std::vector<Eigen::Vector2d>>& phase;  // per strip and scan line
  const Landscape& landscape;
  std::size_t n_c;  // points per scan line
  double da;        // scan line spacing
  std::vector<Eigen::Matrix4d> inverse;
  std::vector<std::size_t> firsts;

  void
  indexStrips()
  {
    for (const auto& st : block.strips) {
      inverse.push_back(st.transform.matrix().inverse());
      firsts.push_back(st.first_index);
    }
  }

  PointLiDAR
  point(std::size_t idx, Random& rng) const
  {
    const std::size_t strip =
        static_cast<std::size_t>(std::upper_bound(firsts.begin(), firsts.end(), idx) - firsts.begin()) - 1;
    const std::size_t local = idx - firsts[strip];
    const std::size_t k = local / n_c, j = local % n_c;
    const double f = (static_cast<double>(j) + 0.5) / static_cast<double>(n_c);
    const Eigen::Vector2d& uv = phase[strip][k];
    const double fu = (static_cast<double>(j) + uv.x()) / static_cast<double>(n_c);
    const bool reverse = s.pattern == ScanPattern::ZIGZAG && (k % 2 == 1);
    const double across = ((reverse ? 1.0 - fu : fu) - 0.5) * s.swath_width;
    const double along_pos = (static_cast<double>(k) + f) * da;
    const double along_ground = along_pos + (uv.y() - 0.5) * da;
    const FlightLine& fl = lines[strip];
    const StripTruth& st = block.strips[strip];
    const Eigen::Vector2d xy = fl.c + (along_ground - 0.5 * fl.length) * fl.d + across * fl.a;
    const Hit hit = landscape.hit(xy.x(), xy.y(), rng);
    const Eigen::Vector4d p(xy.x(), xy.y(), hit.z, 1.0);
    const Eigen::Vector4d noisy = p + (Eigen::Vector4d() << rng.normal3(s.noise_sigma), 0.0).finished();
    PointLiDAR q = detail::makePoint((inverse[strip] * noisy).head<3>());
    q.classification = hit.classification;
    q.intensity = static_cast<float>(hit.intensity_base + rng.uniform(-10.0, 10.0));
    q.point_source_id = st.point_source_id;
    q.gps_time = st.start_time + along_pos / s.speed;
    return q;
  }
};

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
  block.direction = Eigen::Vector2d(std::cos(s.heading), std::sin(s.heading));
  block.strip_spacing = s.swath_width * (1.0 - s.side_overlap);
  const std::size_t n_c =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(s.swath_width * std::sqrt(s.density))));
  const double dc = s.swath_width / static_cast<double>(n_c);
  const double da = 1.0 / (s.density * dc);
  Eigen::AlignedBox2d region;
  const std::vector<FlightLine> lines = layOut(s, block, da, n_c, region);
  drawTruths(s, block.strips);
  const auto phase = drawLinePhases(s, block.strips);

  const Terrain terrain(s.seed, s.relief, s.wavelength);
  auto landscape =
      std::make_shared<Landscape>(terrain, s.landscape, s.buildings, s.building_settings, region, s.seed);
  block.surface = landscape->surface();
  block.landscape = landscape;

  const std::size_t total = block.strips.back().first_index + block.strips.back().point_count;
  auto& cloud = *block.cloud;
  cloud.resize(total);
  cloud.width = static_cast<std::uint32_t>(total);
  cloud.height = 1;
  cloud.is_dense = true;
  StripSampler sampler{s, block, lines, phase, *landscape, n_c, da, {}, {}};
  sampler.indexStrips();
  detail::forEachBlocked(total, s.seed, 0x5791u,
                         [&](std::size_t idx, Random& rng) { cloud[idx] = sampler.point(idx, rng); });
  return block;
}

void
setScene(StripSettings& s, LandscapeType type)
{
  s.landscape = LandscapeSettings();
  s.landscape.type = type;
  s.building_settings = BuildingSettings();
  if (type == LandscapeType::URBAN) {
    s.relief = 4.0;
    s.wavelength = 300.0;
    s.buildings = true;
    s.building_settings.per_hectare = 10.0;
    s.building_settings.gable_fraction = 0.4;
    s.building_settings.hip_fraction = 0.2;
    s.building_settings.max_eave = 18.0;
    s.landscape.trees_per_hectare = 25.0;
    s.landscape.road_spacing = 120.0;
    s.landscape.road_width = 14.0;
  } else if (type == LandscapeType::MOUNTAIN) {
    s.relief = 60.0;
    s.wavelength = 350.0;
    s.buildings = true;
    s.building_settings.per_hectare = 0.5;
    s.building_settings.min_eave = 2.5;
    s.building_settings.max_eave = 4.0;
    s.landscape.landforms.terrace_step = 2.5;
    s.landscape.landforms.terrace_riser = 0.3;
    s.landscape.landforms.scarps = 4;
    s.landscape.trees_per_hectare = 8.0;
  } else {
    const StripSettings defaults;
    s.relief = defaults.relief;
    s.wavelength = defaults.wavelength;
    s.buildings = defaults.buildings;
  }
}

}  // namespace synth
}  // namespace pcl_ls3d
