#pragma once
/// \file strip_tools.h
/// \brief Selections by LAS attributes: flight strips (PointSourceId) and ASPRS classes.

#include <pcl_ls3d/point_types.h>

#include <pcl/point_cloud.h>
#include <pcl/types.h>

#include <cstdint>
#include <map>
#include <set>

namespace pcl_ls3d {
namespace io {

/// Indices of the points of each point-source id (flight strip), in increasing id order; the
/// indices of one strip keep the cloud's order.
std::map<std::uint16_t, pcl::Indices>
splitByPointSource(const pcl::PointCloud<PointLiDAR>& cloud);

/// Indices of the points whose classification is (keep = true) or is not (keep = false) in `classes`.
pcl::Indices
filterByClassification(const pcl::PointCloud<PointLiDAR>& cloud, const std::set<std::uint8_t>& classes,
                       bool keep = true);

}  // namespace io
}  // namespace pcl_ls3d
