#include "matching_steps.h"

#include "rules/target_overlap.h"

#include <pcl_ls3d/adjustment/surface_noise.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace detail {

bool
setUpPair(const std::vector<Eigen::Vector3d>& source, const TargetSurface& target,
          const Eigen::Matrix4d& guess, const AdjustmentSettings& settings, PairSetup& setup,
          std::vector<Eigen::Vector3d>& reduced)
{
  Eigen::Vector3d o_s;
  if (!overlapCentroid(source, target, guess, settings.max_correspondence_distance, o_s, setup.target_box,
                       setup.inside))
    return false;
  setup.source = sourceBlockFromGuess(guess, o_s, settings);
  setup.target = ParameterBlock::fixedIdentity(setup.source.output_origin);

  reduced.resize(source.size());
  setup.radius = 0.0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    reduced[i] = source[i] - o_s;
    if (!reduced[i].allFinite())
      continue;  // SampleConsensusModelSurfaceMatching's epochs may hold NaN points
    setup.radius = std::max(setup.radius, reduced[i].norm());
    setup.source_box.extend(reduced[i]);
  }
  return true;
}

double
sourceNoise(const std::vector<Eigen::Vector3d>& reduced, const PairSetup& setup)
{
  const double area = setup.source_box.sizes().head<2>().prod();
  const double density = area > 0.0 ? static_cast<double>(reduced.size()) / area : 0.0;
  if (!(density > 0.0))
    return 0.0;
  return estimateSurfaceNoise(reduced, setup.inside, std::sqrt(30.0 / (M_PI * density)));
}

double
precisionCell(const AdjustmentSettings& settings, const PairSetup& setup, std::size_t target_size)
{
  if (settings.precision_cell > 0.0)
    return settings.precision_cell;
  const double area = setup.target_box.sizes().head<2>().prod();
  return area > 0.0 ? 8.0 * std::sqrt(area / static_cast<double>(target_size)) : 0.0;
}

std::string
fillPrecision(AdjustmentReport& report, const GaussMarkovSolution& sol)
{
  std::string undetermined;
  // σ0 = 0: every residual vanished (a cloud matched to itself or to a superset of itself).
  // The data say nothing about the spread then; σ = 0 would claim a perfect instrument.
  const bool exact_fit = !(sol.sigma0 > 1e-10);  // rounding of identical coordinates: ~1e-16
  if (exact_fit)
    report.precision_model = "not estimable: exact fit, every residual is 0";
  for (int i = 0; i < 7; ++i) {
    const std::size_t s = static_cast<std::size_t>(i);
    report.sigmas_formal[i] = sol.sigma0 * std::sqrt(sol.qxx(i, i));
    if (sol.fixed[s])
      report.sigmas[i] = report.sigmas_formal[i] = 0.0;
    else if (!sol.determinable[s]) {
      report.sigmas[i] = report.sigmas_formal[i] = std::numeric_limits<double>::infinity();
      undetermined += (undetermined.empty() ? "" : ", ") + similarityParameterNames()[s];
    } else if (exact_fit)
      report.sigmas[i] = report.sigmas_formal[i] = std::numeric_limits<double>::quiet_NaN();
    else
      report.sigmas[i] = std::sqrt(std::max(0.0, report.covariance(i, i)));
    for (int j = 0; j < 7; ++j) {
      const double d = std::sqrt(report.covariance(i, i) * report.covariance(j, j));
      report.correlation(i, j) = d > 0.0 ? report.covariance(i, j) / d : 0.0;
    }
  }
  return undetermined;
}

std::vector<Eigen::Vector3d>
conjugatePoints(const ObservationSet& set, std::size_t most)
{
  std::vector<Eigen::Vector3d> feet;
  const std::size_t step = std::max<std::size_t>(1, set.size() / std::max<std::size_t>(1, most));
  for (std::size_t j = 0; j < set.size() && feet.size() < most; j += step)
    feet.push_back(set[j].foot);
  return feet;
}

std::array<bool, 7>
flags7(const std::vector<bool>& flags)
{
  std::array<bool, 7> out{};
  for (std::size_t i = 0; i < 7 && i < flags.size(); ++i)
    out[i] = flags[i];
  return out;
}

}  // namespace detail
}  // namespace pcl_ls3d
