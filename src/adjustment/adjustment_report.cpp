#include <pcl_ls3d/adjustment/adjustment_report.h>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace pcl_ls3d {

const char*
terminationTypeToString(TerminationType type)
{
  switch (type) {
  case TerminationType::NOT_RUN:
    return "NOT_RUN";
  case TerminationType::CONVERGED:
    return "CONVERGED";
  case TerminationType::MAX_ITERATIONS:
    return "MAX_ITERATIONS";
  case TerminationType::INVALID_INPUT:
    return "INVALID_INPUT";
  case TerminationType::NO_OVERLAP:
    return "NO_OVERLAP";
  case TerminationType::TOO_FEW_OBSERVATIONS:
    return "TOO_FEW_OBSERVATIONS";
  case TerminationType::SINGULAR:
    return "SINGULAR";
  case TerminationType::DIVERGED:
    return "DIVERGED";
  case TerminationType::STALLED:
    return "STALLED";
  case TerminationType::UNRELIABLE:
    return "UNRELIABLE";
  case TerminationType::IMPLAUSIBLE_SCALE:
    return "IMPLAUSIBLE_SCALE";
  }
  return "UNKNOWN";
}

bool
AdjustmentReport::hasEstimate() const
{
  return (isSolutionUsable() || termination == TerminationType::STALLED ||
          termination == TerminationType::UNRELIABLE || termination == TerminationType::IMPLAUSIBLE_SCALE) &&
         parameters.allFinite();
}

bool
AdjustmentReport::isSolutionUsable() const
{
  return (termination == TerminationType::CONVERGED || termination == TerminationType::MAX_ITERATIONS) &&
         parameters.allFinite();
}

std::string
AdjustmentReport::brief() const
{
  char line[256];
  std::snprintf(
      line, sizeof(line), "%s after %d iterations, sigma0 = %.6g, %zu observations used, %zu rejected",
      terminationTypeToString(termination), iterations, sigma0, observations_used, observations_rejected);
  return line;
}

namespace {
std::string
format(const char* fmt, double a, double b = 0.0, double c = 0.0)
{
  char buf[128];
  std::snprintf(buf, sizeof(buf), fmt, a, b, c);
  return buf;
}
}  // namespace

std::string
AdjustmentReport::fullReport() const
{
  std::ostringstream os;
  os << "LS3D adjustment (" << rule_name << ", " << estimator_name << "): " << brief() << "\n";
  if (!message.empty())
    os << "  message: " << message << "\n";
  if (quality.expected_noise > 0.0 || quality.coverage > 0.0)
    os << (quality.noise_yardstick > quality.expected_noise
               ? format("  quality: sigma0 = %.3g x 0.001 x the point spacing (%.3g; the surfaces' own noise "
                        "%.3g is below it)",
                        quality.sigma0_ratio, quality.noise_yardstick, quality.expected_noise)
               : format("  quality: sigma0 = %.3g x the surfaces' own noise (%.3g)", quality.sigma0_ratio,
                        quality.expected_noise))
       << (quality.normal_sigma_ratio > 0.0
               ? format(" (across the surface %.3g x)", quality.normal_sigma_ratio)
               : std::string())
       << format(", coverage %.3f, rejected %.3f", quality.coverage, quality.rejected_fraction)
       << format(", moved %.4g (position sigma %.3g), kept %.3g of the start's correspondences",
                 quality.movement, quality.position_sigma, quality.observations_kept)
       << ": " << (quality.trustworthy ? "trustworthy\n" : "NOT TRUSTWORTHY\n");
  if (quality.held_out_scale_tested)
    os << format("  held-out scale if freed: m - 1 = %+.4g ppm +- %.3g (z %+.3g)",
                 1e6 * quality.held_out_scale, 1e6 * quality.held_out_scale_sigma, quality.held_out_scale_z)
       << format(", moves the source's edge by %.4g\n", quality.held_out_scale_effect);
  os << format("  local origin (source) = (%.4f, %.4f, %.4f)\n", local_origin_source.x(),
               local_origin_source.y(), local_origin_source.z());
  os << format("  local origin (target) = (%.4f, %.4f, %.4f)\n", local_origin_target.x(),
               local_origin_target.y(), local_origin_target.z());
  os << "  source points " << source_points << ", correspondences " << correspondences
     << ", redundancy r = " << redundancy << "\n";
  const auto& names = similarityParameterNames();
  os << "  parameters (reduced frame) +- sigma [" << precision_model << "]:\n";
  if (source_noise > 0.0)
    os << format("  source noise (errors-in-variables correction of m) = %.4g\n", source_noise);
  for (int i = 0; i < 7; ++i) {
    const std::size_t s = static_cast<std::size_t>(i);
    os << "    " << names[s] << (names[s].size() < 5 ? std::string(6 - names[s].size(), ' ') : " ");
    os << format("% .9f", parameters[i]);
    if (fixed[s])
      os << "  (fixed)";
    else if (!determinable[s])
      os << "  (UNDETERMINABLE: held, geometry gives no information)";
    else if (std::isnan(sigmas[i]))
      os << "  +- not estimable (exact fit)";
    else
      os << format("  +- %.3e  (formal %.3e)", sigmas[i], sigmas_formal[i]);
    os << "\n";
  }
  os << "  correlation matrix:\n";
  for (int r = 0; r < 7; ++r) {
    os << "    ";
    for (int c = 0; c < 7; ++c)
      os << format("% .3f ", correlation(r, c));
    os << "\n";
  }
  os << "  iterations:\n";
  for (const IterationRecord& it : log)
    os << format("    %3.0f  sigma0 %.5g", it.iteration, it.sigma0)
       << format("  used %.0f  rejected %.0f", static_cast<double>(it.observations_used),
                 static_cast<double>(it.observations_rejected))
       << format("  dangle %.2e  dt %.2e  dm %.2e", it.max_angle_change, it.translation_change,
                 it.scale_change)
       << (it.extrapolated ? "  (extrapolated)\n" : "\n");
  return os.str();
}

}  // namespace pcl_ls3d
