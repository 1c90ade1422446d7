#include <pcl_ls3d/deformation/deformation_analysis.h>

namespace pcl_ls3d {
namespace deformation {

bool
DeformationSettings::isValid(std::string* why) const
{
  return matching.isValid(why) && residuals.isValid(why) && regions.isValid(why);
}

DeformationResult
analyseDeformation(const std::vector<Eigen::Vector3d>& epoch, const TargetSurface& reference,
                   const ConjugateRule& rule, const DeformationSettings& settings, const Eigen::Matrix4d& guess)
{
  DeformationResult out;
  std::string why;
  if (!settings.isValid(&why)) {
    out.matching.termination = TerminationType::INVALID_INPUT;
    out.matching.message = "invalid settings: " + why;
    return out;
  }
  std::size_t finite = 0;
  for (const Eigen::Vector3d& p : epoch)
    finite += p.allFinite();
  if (settings.matching_points > 0 && finite > settings.matching_points) {
    // Every k-th finite point (k ≥ 1 real-valued, so exactly matching_points are taken).
    std::vector<Eigen::Vector3d> sample;
    std::vector<int> index;
    sample.reserve(settings.matching_points);
    const double step = static_cast<double>(finite) / static_cast<double>(settings.matching_points);
    double next = 0.0;
    std::size_t rank = 0;
    for (std::size_t i = 0; i < epoch.size(); ++i) {
      if (!epoch[i].allFinite())
        continue;
      if (static_cast<double>(rank) >= next && sample.size() < settings.matching_points) {
        sample.push_back(epoch[i]);
        index.push_back(static_cast<int>(i));
        next += step;
      }
      ++rank;
    }
    out.matching = robustMatching(sample, index, reference, rule, settings.matching, guess);
  }
  else
    out.matching = robustMatching(epoch, {}, reference, rule, settings.matching, guess);
  if (!out.matching.isSolutionUsable())
    return out;
  ResidualSettings rs = settings.residuals;
  rs.max_distance = std::min(rs.max_distance, settings.matching.adjustment.max_correspondence_distance);
  out.field = computeResidualField(epoch, reference, rule, out.matching.adjustment, out.matching.scale, rs);
  RegionSettings regions = settings.regions;
  if (regions.plane_axis < 0 && settings.rule == ConjugateRuleType::LZD)
    regions.plane_axis = 2;  // LZD residuals are heights: areas and volumes on the xy plane
  out.regions = analyseRegions(epoch, out.field, regions);
  return out;
}

}  // namespace deformation
}  // namespace pcl_ls3d
