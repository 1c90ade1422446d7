#pragma once
/// \file voxel_baseline.h
/// \brief The granularity baseline of the object-based evaluation: every non-empty cell of a
///        cubic voxel grid is a segment, with the cell size chosen so that the number of
///        segments matches another method's. Whatever a segmentation scores beyond this
///        baseline at the same segment count is what its rules add beyond cutting finely.

#include <pcl/PointIndices.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstddef>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// \brief Segments = non-empty cells of a grid of cubes of edge \a size anchored at the minimum
///        corner of the finite points (non-finite points are in no segment).
std::vector<pcl::PointIndices>
voxelSegments(const pcl::PointCloud<pcl::PointXYZ>& cloud, double size);

/// \brief voxelSegments() with the edge whose segment count is closest to \a target (bisection
///        on log size, count within 1 % or 40 steps). \a size receives the edge used.
std::vector<pcl::PointIndices>
voxelSegmentsWithCount(const pcl::PointCloud<pcl::PointXYZ>& cloud, std::size_t target, double& size);

}  // namespace evaluation
}  // namespace pcl_ls3d
