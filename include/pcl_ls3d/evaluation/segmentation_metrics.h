#pragma once
/// \file segmentation_metrics.h
/// \brief Per-class precision, recall and F1 of a segmentation against reference labels
///        (Wang et al. 2021 §4.1, eq. 3): P = TP/(TP+FP), R = TP/(TP+FN), F1 = 2PR/(P+R).
///
/// Rules (stated, because the paper's own per-object rule needs instance references that
/// classified LAS files do not have):
///  - each segment is mapped to the class group holding most of its evaluated points
///    (ties go to the group listed first); its points are "predicted" as that group;
///  - points whose reference code is excluded (default 0 never classified, 1 unclassified) are
///    left out of everything: they neither vote nor count as TP/FP/FN;
///  - evaluated codes in no group form the pseudo-class "other": they vote, and count as FP of a
///    group whose segment they sit in; "other" itself is reported but not a target class;
///  - evaluated points in no segment are false negatives of their class (predicted "none");
///  - a point listed in several segments counts once, for the first segment listing it;
///  - optionally, segments smaller than min_segment_size are treated as no segment (their points
///    become false negatives). Majority mapping rewards over-segmentation (one point per segment
///    would score F1 = 1), so comparing at the minimum cluster size of pcl::RegionGrowing shows
///    how much of a score rests on fragments.
/// Only pcl::PointIndices is used from PCL.

#include <pcl_ls3d/evaluation/segmentation_classes.h>

#include <pcl/PointIndices.h>

#include <cstddef>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// \brief Counts and scores of one class group. Scores are NaN where undefined (P with no
///        predicted point, R with no reference point, F1 with neither TP nor FP nor FN).
struct ClassScores
{
  std::string name;
  std::size_t reference_points = 0;  ///< evaluated points whose reference is this class
  std::size_t predicted_points = 0;  ///< points of segments mapped to this class (TP + FP)
  std::size_t segments = 0;          ///< segments mapped to this class
  std::size_t tp = 0, fp = 0, fn = 0;
  double precision = 0.0, recall = 0.0, f1 = 0.0;
};

/// \brief Which codes form which class and which are excluded.
struct SegmentationEvaluationSettings
{
  std::vector<ClassGroup> groups = defaultClassGroups();
  std::vector<int> excluded_codes = defaultExcludedCodes();
  std::size_t min_segment_size = 0;  ///< smaller segments count as no segment (0: keep all)
};

/// \brief Result of evaluateSegmentation(). `classes` follows the settings' group order.
struct SegmentationEvaluation
{
  std::string method;    ///< free text set by the caller ("IMRG", ...)
  double seconds = 0.0;  ///< wall time of the method, set by the caller
  std::string failure;   ///< set by the caller when the method failed: a table row
  std::vector<ClassScores> classes;
  ClassScores other;                   ///< pseudo-class "other" (codes in no group)
  std::size_t segments = 0;            ///< segments given
  std::size_t segments_evaluated = 0;  ///< segments with at least one evaluated point
  std::size_t segments_too_small = 0;  ///< segments ignored by min_segment_size
  std::size_t points_total = 0;        ///< size of the reference label vector
  std::size_t points_evaluated = 0;    ///< points not excluded
  std::size_t points_unsegmented = 0;  ///< evaluated points in no segment (all FN)
  std::size_t points_duplicated = 0;   ///< extra listings of a point already in a segment
  /// confusion[r][c]: r = reference group (G = other), c = predicted group (G = other, G+1 = none).
  std::vector<std::vector<std::size_t>> confusion;
};

/// \brief Evaluates `segments` (indices into a cloud of reference_labels.size() points).
/// \return false with a one-line reason (index out of range) in `error`
bool
evaluateSegmentation(const std::vector<pcl::PointIndices>& segments, const std::vector<int>& reference_labels,
                     const SegmentationEvaluationSettings& settings, SegmentationEvaluation& result,
                     std::string& error);

/// \brief Scores predicted classes point by point (IMRG's object classes, as LAS codes): a point
///        is predicted as the group holding its predicted code; a predicted code in no group or
///        excluded is predicted "other" or "none", and 0 (no segment) and 1 (unclassified) are
///        always "none" (a false negative of the point's class), even when a group names code 1
///        for the reference (IGN's parked cars). Reference points with excluded codes are left
///        out, as above; min_segment_size does not apply (there are no segments).
///        method, seconds and segments are kept from \a result (the caller's); the per-class
///        segment counts stay 0; points_unsegmented counts the points predicted none.
/// \return false with a one-line reason (sizes differ) in `error`
bool
evaluateClassification(const std::vector<int>& predicted_codes, const std::vector<int>& reference_labels,
                       const SegmentationEvaluationSettings& settings, SegmentationEvaluation& result,
                       std::string& error);

/// \brief Scores from counts: the rules of ClassScores (exposed for tests and tools).
void
computeScores(ClassScores& s);

}  // namespace evaluation
}  // namespace pcl_ls3d
