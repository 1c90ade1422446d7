#pragma once
/// \file roof_cover.h
/// \brief What lies under a roof is the building: points of vegetation objects under a
///        building's roof in plan join that building. PCL-free.
///
/// An airborne scanner records nothing of a crown under a roof; what it records below a roof,
/// inside the roof's outline, is the building itself — facade points between the eaves and the
/// crowns in front of it, balconies, a porch. The growth puts such scattered facade points into
/// the crowns they touch (rough with rough), and a tree group then holds a strip of its
/// neighbour's wall. Roof cells are the plan cells (edge \a cell) holding points of a building
/// object's solid segments (point_kind Solid: its roof planes); a point of a vegetation object
/// in such a cell lower than the cell's lowest roof point by more than \a clearance joins the
/// building whose roof point is the highest in that cell. A crown over a roof (above it) and
/// a crown beside it (outside its cells) stay vegetation; other classes are left alone (a car
/// under a carport is no part of it). Crown points that the growth put into a roof plane give
/// roof cells too, and what lies under them joins the building: the one error this rule can
/// spread (docs/BENCHMARKS.md, "what is left").

#include <pcl_ls3d/segmentation/object_classes.h>
#include <pcl_ls3d/segmentation/segment_kinds.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {

/// \brief Moves the vegetation points under building roofs into those buildings (rule above).
/// \param[in] points coordinates per point (non-finite ones are left alone)
/// \param[in] point_kind per point: kind of its segment before the assembly joined any
/// \param[in] object_class per object (index = label), classifyObjects()
/// \param[in] cell edge of the plan cells [m]
/// \param[in] clearance how far below the cell's lowest roof point a point must lie [m]
/// \param[in,out] labels object per point (−1 none)
/// \return the number of points moved; 0 when the sizes differ or cell is not positive
std::size_t
claimPointsUnderRoofs(const std::vector<Eigen::Vector3f>& points, const std::vector<SegmentKind>& point_kind,
                      const std::vector<ObjectClass>& object_class, double cell, double clearance,
                      std::vector<int>& labels);

}  // namespace segmentation
}  // namespace pcl_ls3d
