#include <pcl_ls3d/synth/landforms.h>
#include <pcl_ls3d/synth/random.h>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {
namespace synth {

namespace {

// 0 below 0, 1 above 1, 3t² − 2t³ between.
double
smoothstep(double t)
{
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

bool
LandformSettings::isValid(std::string* why) const
{
  auto fail = [why](const char* msg) {
    if (why)
      *why = msg;
    return false;
  };
  if (!(terrace_step >= 0.0) || !(terrace_riser > 0.0 && terrace_riser <= 1.0))
    return fail("terrace_step must be >= 0 and terrace_riser in (0, 1]");
  if (scarps < 0 || !(min_scarp_height >= 0.0 && max_scarp_height >= min_scarp_height) ||
      !(scarp_width > 0.0))
    return fail("scarps >= 0, 0 <= min_scarp_height <= max_scarp_height, scarp_width > 0");
  return true;
}

Ground::Ground(Terrain terrain, const LandformSettings& settings, const Eigen::AlignedBox2d& region,
               std::uint32_t seed)
    : terrain_(std::move(terrain)), settings_(settings)
{
  Random rng(seed, 0x5ca7u, 0u);
  for (int k = 0; k < settings.scarps; ++k) {
    Scarp s;
    const double a = rng.uniform(0.0, 2.0 * M_PI);
    s.normal = Eigen::Vector2d(std::cos(a), std::sin(a));
    s.point = region.min() +
              Eigen::Vector2d(rng.uniform(0.2, 0.8), rng.uniform(0.2, 0.8)).cwiseProduct(region.sizes());
    s.height = rng.uniform(settings.min_scarp_height, settings.max_scarp_height);
    scarps_.push_back(s);
  }
}

double
Ground::height(double x, double y) const
{
  double h = terrain_.height(x, y);
  const double S = settings_.terrace_step;
  if (S > 0.0) {
    const double k = std::floor(h / S), f = h / S - k, w = settings_.terrace_riser;
    h = S * (k + smoothstep((f - 1.0 + w) / w));
  }
  const Eigen::Vector2d p(x, y);
  for (const Scarp& s : scarps_)
    h += s.height * smoothstep(s.normal.dot(p - s.point) / settings_.scarp_width + 0.5);
  return h;
}

}  // namespace synth
}  // namespace pcl_ls3d
