#pragma once
/// \file segmentation_report.h
/// \brief Plain-text output of segmentation evaluations: one comparison table (method, segments,
///        time, per-class P/R/F1) and a short confusion diagnosis per method.

#include <pcl_ls3d/evaluation/object_metrics.h>
#include <pcl_ls3d/evaluation/segmentation_metrics.h>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// \brief One row per evaluation; classes in the order of the first evaluation; percentages
///        with one decimal, "-" for an undefined score. Classes with no reference point and no
///        predicted point in every evaluation are left out.
std::string
formatSegmentationTable(const std::vector<SegmentationEvaluation>& evaluations);

/// \brief Object-based table (Wang et al. 2021 §4.1): per method and class, P / R / F1 over the
///        recognised objects. Classes without objects in the first evaluation are left out.
std::string
formatObjectTable(const std::vector<ObjectEvaluation>& evaluations);

/// \brief Fragmentation table: per method and class, recognised / all objects, and over objects
///        of at least `min_points` points the median number of valid segments per object and the
///        median share of the largest valid segment.
std::string
formatFragmentationTable(const std::vector<ObjectEvaluation>& evaluations, std::size_t min_points);

/// \brief Where each class's points went, e.g. "building: 91.2% building, 6.1% ground,
///        2.7% none" — the largest flows only (those above `min_share`).
std::string
describeConfusion(const SegmentationEvaluation& evaluation, double min_share = 0.01);

}  // namespace evaluation
}  // namespace pcl_ls3d
