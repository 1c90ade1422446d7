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
