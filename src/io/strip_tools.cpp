/// \file strip_tools.cpp
/// \brief splitByPointSource() and filterByClassification().

#include <pcl_ls3d/io/strip_tools.h>

namespace pcl_ls3d {
namespace io {

std::map<std::uint16_t, pcl::Indices>
splitByPointSource(const pcl::PointCloud<PointLiDAR>& cloud)
{
  std::map<std::uint16_t, pcl::Indices> strips;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    strips[cloud[i].point_source_id].push_back(static_cast<pcl::index_t>(i));
  return strips;
}

pcl::Indices
filterByClassification(const pcl::PointCloud<PointLiDAR>& cloud, const std::set<std::uint8_t>& classes,
                       bool keep)
{
  pcl::Indices indices;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if ((classes.count(cloud[i].classification) > 0) == keep)
      indices.push_back(static_cast<pcl::index_t>(i));
  return indices;
}

}  // namespace io
}  // namespace pcl_ls3d
