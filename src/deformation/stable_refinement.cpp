#include <pcl_ls3d/common/voxel_index.h>
#include <pcl_ls3d/deformation/stable_refinement.h>
#include <pcl_ls3d/evaluation/transform_error.h>

#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace deformation {

namespace {

struct LeftOut
{
  std::vector<std::uint8_t> mask;  // per point: in a region or its rim
  std::size_t count = 0;           // observed points in the mask
  std::size_t observed = 0;
  std::size_t regions = 0;  // regions found
};

// The regions of `analysis` (of `field`) and their rim; with `largest` > 0 only regions
// 1..largest (regions are numbered by decreasing area).
LeftOut
regionsAndRim(const std::vector<Eigen::Vector3d>& points, const ResidualField& field, RegionAnalysis analysis,
              int plane_axis, std::size_t largest = 0)
{
  LeftOut out;
  out.observed = field.observed;
  out.regions = analysis.regions.size();
  if (largest > 0)
    for (int& id : analysis.region)
      id = id > 0 && static_cast<std::size_t>(id) <= largest ? id : 0;
  out.mask = nearRegions(points, analysis, plane_axis);
  for (std::size_t i = 0; i < points.size(); ++i)
    out.count += out.mask[i] && std::isfinite(field.residual[i]) ? 1 : 0;
  return out;
}

// What is left out is found first on neighbourhood means (LOD95): a patch the robust fit has
// partly absorbed (3 σ showing as 1.5 σ) is below the point-wise 3 σ test almost everywhere, but
// its mean over 12 neighbours stands √12 times clearer of the noise. When the fit is tilted the
// means flag the tilt too; then the point-wise test (the user's) is used, and when that also
// flags more than `max_share`, only its largest regions that stay within it: a fit tilted
// towards a large patch flags the far side of the stable part as well, and leaving the patch
// alone out lets the next round correct the tilt.
LeftOut
leftOut(const std::vector<Eigen::Vector3d>& points, const TargetSurface& reference, const ConjugateRule& rule,
        const RobustMatchingReport& robust, const ResidualSettings& residuals, const RegionSettings& regions,
        double max_share)
{
  ResidualSettings by_means = residuals;
  by_means.rule = DetectionRule::LOD95;
  const ResidualField means =
      computeResidualField(points, reference, rule, robust.adjustment, robust.scale, by_means);
  const double max_count = max_share * static_cast<double>(means.observed);
  LeftOut left = regionsAndRim(points, means, analyseRegions(points, means, regions), regions.plane_axis);
  if (static_cast<double>(left.count) <= max_count)
    return left;
  const ResidualField own =
      computeResidualField(points, reference, rule, robust.adjustment, robust.scale, residuals);
  const RegionAnalysis analysis = analyseRegions(points, own, regions);
  left = regionsAndRim(points, own, analysis, regions.plane_axis);
  for (std::size_t largest = 1; static_cast<double>(left.count) > max_count && largest < left.regions;
       ++largest) {
    LeftOut fewer = regionsAndRim(points, own, analysis, regions.plane_axis, largest);
    if (static_cast<double>(fewer.count) > max_count)
      break;
    left = std::move(fewer);
  }
  return left;
}

}  // namespace

RobustMatchingSettings
stablePartMatching(const RobustMatchingSettings& robust)
{
  RobustMatchingSettings m = robust;
  m.method = RobustMethod::M;
  m.constant = std::numeric_limits<double>::quiet_NaN();
  m.least_squares_start = false;
  return m;
}

void
keepHighBreakdownFigures(const RobustMatchingReport& robust, RobustMatchingReport& refined)
{
  refined.method = robust.method;
  refined.start = robust.start;
  refined.search = robust.search;
  refined.rounds = robust.rounds;
  refined.subsets_drawn = robust.subsets_drawn;
  refined.high_breakdown_transformation = robust.high_breakdown_transformation;
  refined.high_breakdown_scale = robust.high_breakdown_scale;
  refined.neighbour_noise = robust.neighbour_noise;
  refined.block_start_transformation = robust.block_start_transformation;
  refined.block_support = robust.block_support;
  refined.held_out = robust.held_out;
  refined.iterations += robust.iterations;
}

bool
StableRefinementSettings::isValid(std::string* why) const
{
  if (max_rounds >= 0 && max_left_out > 0.0 && max_left_out <= 1.0)
    return true;
  if (why)
    *why = "stable refinement: max_rounds must be >= 0 and max_left_out in (0, 1]";
  return false;
}

std::vector<std::uint8_t>
nearRegions(const std::vector<Eigen::Vector3d>& points, const RegionAnalysis& analysis, int plane_axis)
{
  const std::size_t n = points.size();
  std::vector<std::uint8_t> out(n, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Eigen::Vector3d> link(n, Eigen::Vector3d::Constant(nan));
  for (std::size_t i = 0; i < n; ++i) {
    if (!points[i].allFinite())
      continue;
    link[i] = points[i];
    if (plane_axis >= 0 && plane_axis < 3)
      link[i][plane_axis] = 0.0;
  }
  std::vector<Eigen::Vector3d> members(n, Eigen::Vector3d::Constant(nan));
  for (std::size_t i = 0; i < n; ++i)
    if (analysis.region[i] > 0)
      members[i] = link[i];
  const double radius = analysis.adjacency;
  const VoxelIndex index(members, std::max(radius, 1e-9));
  std::vector<int> near;
  for (std::size_t i = 0; i < n; ++i) {
    if (analysis.region[i] > 0) {
      out[i] = 1;
      continue;
    }
    if (!link[i].allFinite())
      continue;
    index.radiusSearch(link[i], radius, near);
    out[i] = near.empty() ? 0 : 1;
  }
  return out;
}

StableRefinementReport
refineOnStablePart(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& point_indices,
                   const TargetSurface& reference, const ConjugateRule& rule,
                   const RobustMatchingSettings& matching, const ResidualSettings& residuals,
                   const RegionSettings& regions, const StableRefinementSettings& settings,
                   RobustMatchingReport& robust)
{
  StableRefinementReport report;
  report.stopped = "off";
  if (settings.max_rounds <= 0)
    return report;
  const RobustMatchingSettings m = stablePartMatching(matching);
  Eigen::Matrix3Xd sample(3, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    sample.col(static_cast<Eigen::Index>(i)) = points[i];
  std::vector<std::uint8_t> previous;
  for (int round = 1; round <= settings.max_rounds; ++round) {
    const LeftOut left = leftOut(points, reference, rule, robust, residuals, regions, settings.max_left_out);
    if (left.regions == 0) {
      report.stopped = "no deformed region";
      return report;
    }
    if (left.count > settings.max_left_out * static_cast<double>(left.observed)) {
      report.stopped = "the regions cover more than " +
                       std::to_string(static_cast<int>(100.0 * settings.max_left_out)) +
                       " % of the observed points";
      return report;
    }
    if (left.mask == previous) {
      report.stopped = "the left-out points did not change";
      return report;
    }
    std::vector<Eigen::Vector3d> kept;
    std::vector<int> kept_indices;
    selectPoints(
        points, point_indices, [&](std::size_t i) { return !left.mask[i]; }, kept, kept_indices);
    RobustMatchingReport refined =
        robustMatching(kept, kept_indices, reference, rule, m, robust.adjustment.transformation);
    if (!refined.isSolutionUsable()) {
      report.stopped = "the stable part's matching failed: " + refined.message;
      return report;
    }
    keepHighBreakdownFigures(robust, refined);
    const double moved = evaluation::computeTransformError(refined.adjustment.transformation,
                                                           robust.adjustment.transformation, sample)
                             .max_bbox;
    robust = std::move(refined);
    previous = left.mask;
    report.rounds = round;
    report.left_out = left.count;
    // As the subset search's re-linearisation: a move below a tenth of σ̂ changes no region.
    if (moved < 0.1 * robust.scale) {
      report.stopped = "the estimate moved less than 0.1 sigma_hat";
      return report;
    }
  }
  report.stopped = "max rounds";
  return report;
}

}  // namespace deformation
}  // namespace pcl_ls3d
