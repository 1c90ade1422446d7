/// \file roof_cover.cpp
/// \brief Vegetation points under a building's roof join the building (roof_cover.h).

#include <pcl_ls3d/segmentation/roof_cover.h>

#include "terrain_cells.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace pcl_ls3d {
namespace segmentation {
namespace {

/// A roof cell: its lowest roof point and the building owning its highest one.
struct RoofCell
{
  float lowest = 0.0f;
  float highest = 0.0f;
  int building = -1;
};

using RoofCells = std::unordered_map<std::uint64_t, RoofCell>;

/// Plan cells holding points of the buildings' solid segments (their roof planes).
RoofCells
roofCells(const std::vector<Eigen::Vector3f>& points, const std::vector<SegmentKind>& point_kind,
          const std::vector<ObjectClass>& object_class, double cell, const std::vector<int>& labels)
{
  RoofCells cells;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Eigen::Vector3f& x = points[p];
    if (point_kind[p] != SegmentKind::Solid || !x.allFinite() ||
        classOf(labels[p], object_class) != ObjectClass::Building)
      continue;
    const auto [it, fresh] =
        cells.try_emplace(detail::planCellOf(x, cell), RoofCell{x.z(), x.z(), labels[p]});
    RoofCell& c = it->second;
    if (fresh)
      continue;
    c.lowest = std::min(c.lowest, x.z());
    if (x.z() > c.highest) {
      c.highest = x.z();
      c.building = labels[p];
    }
  }
  return cells;
}

}  // namespace

std::size_t
claimPointsUnderRoofs(const std::vector<Eigen::Vector3f>& points, const std::vector<SegmentKind>& point_kind,
                      const std::vector<ObjectClass>& object_class, double cell, double clearance,
                      std::vector<int>& labels)
{
  if (point_kind.size() != points.size() || labels.size() != points.size() || !(cell > 0.0))
    return 0;
  const RoofCells roofs = roofCells(points, point_kind, object_class, cell, labels);
  std::size_t moved = 0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Eigen::Vector3f& x = points[p];
    if (!x.allFinite() || classOf(labels[p], object_class) != ObjectClass::Vegetation)
      continue;
    const auto it = roofs.find(detail::planCellOf(x, cell));
    if (it == roofs.end() || !(x.z() < it->second.lowest - clearance))
      continue;
    labels[p] = it->second.building;
    ++moved;
  }
  return moved;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
