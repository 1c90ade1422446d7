#include <pcl_ls3d/strips/strip_adjustment_settings.h>

#include <cmath>

namespace pcl_ls3d {
namespace strips {

AdjustmentSettings
StripAdjustmentSettings::blockAdjustmentDefaults()
{
  AdjustmentSettings s;
  s.translation_epsilon = 1e-4;
  s.coarse_observations = 15000;
  return s;
}

bool
StripAdjustmentSettings::isValid(std::string* why) const
{
  auto fail = [why](const std::string& msg) {
    if (why)
      *why = msg;
    return false;
  };
  if (!(footprint_cell >= 0.0 && std::isfinite(footprint_cell)))
    return fail("footprint_cell must be >= 0");
  if (!(min_overlap_area >= 0.0 && std::isfinite(min_overlap_area)))
    return fail("min_overlap_area must be >= 0");
  if (!(observation_spacing >= 0.0 && std::isfinite(observation_spacing)))
    return fail("observation_spacing must be >= 0");
  if (max_observations < 10)
    return fail("max_observations must be >= 10");
  if (!(roughness_factor > 0.0))
    return fail("roughness_factor must be > 0");
  if (!(max_distance > 0.0 && std::isfinite(max_distance)))
    return fail("max_distance must be a finite positive length");
  if (adjustment.max_iterations < 1)
    return fail("max_iterations must be >= 1");
  if (!(adjustment.angle_epsilon > 0.0 && adjustment.translation_epsilon > 0.0 &&
        adjustment.scale_epsilon > 0.0))
    return fail("the convergence epsilons must be > 0");
  if (!(adjustment.freeze_sigma_fraction > 0.0))
    return fail("freeze_sigma_fraction must be > 0");
  if (!(adjustment.precision_cell >= 0.0 && std::isfinite(adjustment.precision_cell)))
    return fail("precision_cell must be >= 0");
  if (soft_datum && !(soft_sigmas.minCoeff() > 0.0 && soft_sigmas.allFinite()))
    return fail("soft datum sigmas must be finite and > 0");
  for (int r : reference_strips)
    if (r < 0)
      return fail("reference strip indices must be >= 0");
  if (!(adjustment.held_out_z > 0.0) || !(adjustment.held_out_noise_factor >= 0.0) ||
      std::isinf(adjustment.held_out_noise_factor))
    return fail("held_out_z must be > 0 (+inf switches the test off), held_out_noise_factor >= 0 and finite");
  return true;
}

}  // namespace strips
}  // namespace pcl_ls3d
