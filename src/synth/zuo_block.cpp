#include <pcl_ls3d/synth/zuo_block.h>

#include <cmath>

namespace pcl_ls3d {
namespace synth {

namespace {

Vector7d
error(double tx, double ty, double tz, double phi_deg, double omega_deg, double kappa_deg, double m)
{
  const double deg = M_PI / 180.0;
  return (Vector7d() << tx, ty, tz, phi_deg * deg, omega_deg * deg, kappa_deg * deg, m).finished();
}

}  // namespace

std::vector<Vector7d>
zuoErrors(LandscapeType type)
{
  const Vector7d identity = error(0, 0, 0, 0, 0, 0, 1.0);
  if (type == LandscapeType::MOUNTAIN)  // Henan 1&2, 3&2
    return {error(-1.960, 3.614, -3.226, 0.00085, 0.0780, -0.0023, 1.000046), identity,
            error(-2.275, 1.911, -1.334, 0.00014, 0.0320, -0.0052, 0.99998)};
  // Hebei 1&2, 3&2 (3&2's scale 0.99978 capped at −80 ppm)
  return {error(-0.586, 1.799, -3.345, 0.00059, 0.0670, 0.0056, 0.99997), identity,
          error(0.238, 0.461, -0.364, 0.0024, 0.0127, 0.0097, 0.99992)};
}

StripSettings
zuoBlock(LandscapeType type, double scale, std::uint32_t seed)
{
  StripSettings s;
  setScene(s, type);
  s.seed = seed;
  s.num_strips = 3;
  s.strip_length = 1999.0 * scale;
  const bool urban = type != LandscapeType::MOUNTAIN;
  s.swath_width = (urban ? 1548.0 : 2514.0) * scale;
  s.side_overlap = urban ? 0.17 : 0.14;
  s.density = urban ? 4.1 : 2.3;
  s.noise_sigma = 0.05;
  s.fix_first = false;
  s.errors = zuoErrors(type);
  return s;
}

}  // namespace synth
}  // namespace pcl_ls3d
