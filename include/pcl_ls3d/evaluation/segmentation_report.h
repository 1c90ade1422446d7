#pragma once
/// \file segmentation_report.h
/// \brief Plain-text output of segmentation evaluations: one comparison table (method, segments,
///        time, per-class P/R/F1) and a short confusion diagnosis per method.

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

/// \brief Where each class's points went, e.g. "building: 91.2% building, 6.1% ground,
///        2.7% none" — the largest flows only (those above `min_share`).
std::string
describeConfusion(const SegmentationEvaluation& evaluation, double min_share = 0.01);

}  // namespace evaluation
}  // namespace pcl_ls3d
