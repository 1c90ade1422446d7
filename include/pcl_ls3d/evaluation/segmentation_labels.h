#pragma once
/// \file segmentation_labels.h
/// \brief Conversions between segments (std::vector<pcl::PointIndices>) and one label per point
///        (0 = in no segment, s + 1 = segment s), and a stable colour per segment id.

#include <pcl_ls3d/segmentation/object_classes.h>

#include <pcl/PointIndices.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// \brief Label per point: 0 for points in no segment, s + 1 for points of segments[s]
///        (the first segment wins for a point listed twice; indices out of range are ignored).
std::vector<std::uint32_t>
labelsFromSegments(const std::vector<pcl::PointIndices>& segments, std::size_t num_points);

/// \brief Segments from per-point labels: label 0 is "no segment"; the other labels become
///        segments in ascending label order, indices ascending. Empty labels give no segment.
std::vector<pcl::PointIndices>
segmentsFromLabels(const std::vector<std::uint32_t>& labels);

/// \brief Per point: the LAS code of its segment's class (segmentation::lasCode(); 0 for points
///        in no segment; the first segment wins for a point listed twice). Empty \a classes, or
///        one of another size than \a segments: all 0.
std::vector<int>
classCodesFromSegments(const std::vector<pcl::PointIndices>& segments,
                       const std::vector<segmentation::ObjectClass>& classes, std::size_t num_points);

/// \brief A deterministic, well spread RGB colour for a segment label (label 0: grey 128).
///        Packed as 0x00RRGGBB, ready for pcl::PointXYZRGB(L)::rgba.
std::uint32_t
segmentColour(std::uint32_t label);

}  // namespace evaluation
}  // namespace pcl_ls3d
