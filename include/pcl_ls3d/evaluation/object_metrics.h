#pragma once
/// \file object_metrics.h
/// \brief Object-based evaluation of a segmentation (Wang et al. 2021 §4.1) and the two figures
///        that show fragmentation.
///
/// The paper's rules, with S_i a segment and S_r a reference object (ReferenceObjects):
///  1. S_i is a *valid* segment of S_r when more than half of S_i's labelled points lie in S_r
///     (labelled = not of an excluded code; a segment is valid for at most one object);
///  2. S_r is *recognised* when its valid segments together hold more than half of its points;
///  3. for a recognised S_r: TP += |S_i ∩ S_r| and FP += |S_i \ S_r| (labelled points) over its
///     valid segments, FN += |S_r| − Σ|S_i ∩ S_r|; an unrecognised S_r adds |S_r| to FN.
///  P, R, F1 (eq. 3) per class group from the sums over the group's objects. Segments valid for
///  no object, or for an unrecognised one, add nothing (as in the paper).
/// Fragmentation, per object: the number of valid segments and the largest valid segment's
/// share max_i |S_i ∩ S_r| / |S_r| (0 without a valid segment: a building swallowed by the
/// ground segment is not "whole"). Per class: medians over objects of at least
/// min_object_points points.

#include <pcl_ls3d/evaluation/reference_objects.h>

#include <pcl/PointIndices.h>

#include <cstddef>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// \brief What the evaluation found for one reference object.
struct ObjectResult
{
  int group = -1;  ///< class group (ClassLookup::kOther for "other")
  std::size_t points = 0;
  std::size_t valid_segments = 0;
  std::size_t matched_points = 0;  ///< Σ |S_i ∩ S_r| over valid segments
  double largest_share = 0.0;      ///< largest valid segment's share of the object
  bool recognised = false;
};

/// \brief Scores of one class group. P/R/F1 NaN where undefined (see computeScores()).
struct ObjectClassScores
{
  std::string name;
  std::size_t objects = 0, recognised = 0;
  std::size_t tp = 0, fp = 0, fn = 0;
  double precision = 0.0, recall = 0.0, f1 = 0.0;
  std::size_t large_objects = 0;       ///< objects of at least min_object_points
  double median_valid_segments = 0.0;  ///< over large objects (NaN if none)
  double median_largest_share = 0.0;   ///< over large objects (NaN if none)
};

struct ObjectEvaluationSettings
{
  std::size_t min_object_points = 200;  ///< objects counted in the fragmentation medians
};

struct ObjectEvaluation
{
  std::string method;    ///< free text set by the caller
  double seconds = 0.0;  ///< set by the caller
  std::string failure;   ///< set by the caller when the method failed: shown as a table row
  std::size_t segments = 0;
  std::vector<ObjectClassScores> classes;  ///< one per class group, in group order
  std::vector<ObjectResult> objects;       ///< one per reference object
};

/// \brief Evaluates \a segments (indices into the cloud of \a reference) by the rules above.
///        \a result's method and seconds are kept.
/// \return false with a one-line reason (an index outside the reference)
bool
evaluateObjects(const std::vector<pcl::PointIndices>& segments, const ReferenceObjects& reference,
                const ObjectEvaluationSettings& settings, ObjectEvaluation& result, std::string& error);

}  // namespace evaluation
}  // namespace pcl_ls3d
