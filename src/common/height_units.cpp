#include <pcl_ls3d/common/height_units.h>

namespace pcl_ls3d {

namespace {

Eigen::Matrix4d
heightScale(double factor)
{
  Eigen::Matrix4d S = Eigen::Matrix4d::Identity();
  S(2, 2) = factor;
  return S;
}

}  // namespace

Eigen::Matrix4d
HeightUnits::toFiles(const Eigen::Matrix4d& T_working) const
{
  return heightScale(1.0 / target) * T_working * heightScale(source);
}

Eigen::Matrix4d
HeightUnits::toWorking(const Eigen::Matrix4d& T_files) const
{
  return heightScale(target) * T_files * heightScale(1.0 / source);
}

}  // namespace pcl_ls3d

namespace pcl_ls3d {

nlohmann::json
heightUnitsJson(const HeightUnits& heights)
{
  if (!heights.converts())
    return nullptr;
  return {{"plan_units_per_height_unit", {{"target", heights.target}, {"source", heights.source}}},
          {"note", "heights were multiplied by these factors for the matching: parameters, sigmas, "
                   "the reduced frame's origins, residuals and errors are in working coordinates "
                   "(heights in the plan unit); 'transformation', the clouds' origins and positions "
                   "of regions and centroids are in the files' own units"}};
}

}  // namespace pcl_ls3d
