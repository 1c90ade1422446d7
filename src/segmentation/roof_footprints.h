#pragma once
/// \file roof_footprints.h
/// \brief Internal: the footprint rules of the object assembly (object_assembly.h): buildings
///        whose roofs touch in plan join, and what lies on or under a building's roof in plan
///        joins it. Not installed API.

#include "assembly_groups.h"

#include <pcl_ls3d/segmentation/object_assembly.h>

#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {
namespace detail {

/// \brief Joins buildings whose roofs touch in plan, then every non-ground group lying (in
///        plan) on or under one building's roof, within footprint_margin of it, when it is small
///        beside the building or lies below its roof; above the roof, margin cells that open
///        onto what lies beyond it do not count (rules in roof_footprints.cpp).
///        \a building (per segment, all 0 at first) remembers between passes which groups are
///        buildings, so a building stays one after a rough facade has joined it.
void
attachUnderRoofs(const Contacts& c, const std::vector<SegmentKind>& kind, const AssemblySettings& s,
                 Groups& groups, std::vector<char>& building);

/// \brief Per segment, where it lies against the roofs of the buildings formed so far (the
///        groups mostly in roof and wall segments): +1 if it hangs under one (footprint_share of
///        its points under that building's own roof cells in plan, below its roof: a balcony row,
///        a rough facade), −1 if it lies mostly outside every roof (footprint_share of its points
///        not so), 0 otherwise. Ground segments are 0. \a groups is not changed.
std::vector<std::int8_t>
roofSides(const Contacts& c, const std::vector<SegmentKind>& kind, const AssemblySettings& s,
          const Groups& groups);

}  // namespace detail
}  // namespace segmentation
}  // namespace pcl_ls3d
