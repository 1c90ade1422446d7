#pragma once
/// \file segment_report.h
/// \brief pcl_ls3d_segment's JSON report of runs and evaluations, and the one-line summary of
///        IMRG's object classes.

#include <pcl_ls3d/evaluation/object_metrics.h>
#include <pcl_ls3d/evaluation/segmentation_metrics.h>
#include <pcl_ls3d/evaluation/segmentation_runner.h>
#include <pcl_ls3d/segmentation/object_classes.h>

#include "tool_output.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace tools {
namespace segment_report {

using json = nlohmann::json;
namespace ev = pcl_ls3d::evaluation;

inline json
runToJson(const ev::SegmentationRun& r)
{
  json j;
  j["method"] = ev::toString(r.method);
  j["segments"] = r.segments.size();
  j["segments_before_merging"] = r.segments_before_merge;
  j["segments_after_merging"] = r.segments_after_merge;
  j["merges"] = r.merges;
  j["thresholds"] = {
      {"v_t_m", finiteOrNull(r.residual_threshold)},   {"d_t_m", finiteOrNull(r.distance_threshold)},
      {"s_t_m", finiteOrNull(r.similarity_threshold)}, {"V_t", finiteOrNull(r.volume_threshold)},
      {"distance_samples", r.distance_samples},        {"volume_samples", r.volume_samples}};
  j["spacing_m"] = finiteOrNull(r.spacing);
  j["growth_radius_m"] = finiteOrNull(r.growth_radius);
  j["volumetric_radius_m"] = finiteOrNull(r.volumetric_radius);
  j["dimensionality"] = {
      {"linear", r.linear}, {"planar", r.planar}, {"volumetric", r.volumetric}, {"invalid", r.invalid}};
  j["fragments_absorbed"] = r.fragments_absorbed;
  // Segments whose convex hull is degenerate (decided before qhull, which runs silently).
  j["segment_hulls"] = {{"tiny", r.hulls_tiny},
                        {"collinear", r.hulls_collinear},
                        {"flat", r.hulls_flat},
                        {"solid", r.hulls_solid}};
  j["seconds"] = {{"total", r.seconds_total},
                  {"normals", r.seconds_normals},
                  {"segmentation", r.seconds_segmentation},
                  {"search", r.seconds_search},
                  {"features", r.seconds_features},
                  {"growing", r.seconds_growing},
                  {"merging", r.seconds_merging},
                  {"absorbing", r.seconds_absorbing}};
  return j;
}

/// P, R, F1 (null where undefined) and the counts of one class, per point or per object.
template <typename Scores>
inline json
scoresJson(const Scores& c)
{
  return {{"precision", finiteOrNull(c.precision)},
          {"recall", finiteOrNull(c.recall)},
          {"f1", finiteOrNull(c.f1)},
          {"tp", c.tp},
          {"fp", c.fp},
          {"fn", c.fn}};
}

inline json
evaluationToJson(const ev::SegmentationEvaluation& e)
{
  json j;
  j["method"] = e.method;
  j["seconds"] = e.seconds;
  j["segments"] = e.segments;
  j["points_evaluated"] = e.points_evaluated;
  j["points_unsegmented"] = e.points_unsegmented;
  j["segments_under_min_size"] = e.segments_too_small;
  for (const auto& c : e.classes) {
    json& k = j["classes"][c.name] = scoresJson(c);
    k["reference_points"] = c.reference_points;
    k["segments"] = c.segments;
  }
  return j;
}

inline json
objectEvaluationToJson(const ev::ObjectEvaluation& e)
{
  json j;
  j["method"] = e.method;
  j["seconds"] = e.seconds;
  j["segments"] = e.segments;
  if (!e.failure.empty()) {
    j["failure"] = e.failure;
    return j;
  }
  for (const auto& c : e.classes) {
    json& k = j["classes"][c.name] = scoresJson(c);
    k["objects"] = c.objects;
    k["recognised"] = c.recognised;
    k["large_objects"] = c.large_objects;
    k["median_valid_segments"] = finiteOrNull(c.median_valid_segments);
    k["median_largest_share"] = finiteOrNull(c.median_largest_share);
  }
  return j;
}

/// Segments and points per class (IMRG), e.g. "building 12 (30.2 %)", and the same as JSON:
/// per class name {segments, points} (objects, or planes with -level planes).
inline std::string
classSummary(const std::vector<pcl::PointIndices>& segments,
             const std::vector<segmentation::ObjectClass>& classes, std::size_t points, json& j)
{
  std::map<segmentation::ObjectClass, std::pair<std::size_t, std::size_t>> per;
  for (std::size_t s = 0; s < segments.size() && s < classes.size(); ++s) {
    ++per[classes[s]].first;
    per[classes[s]].second += segments[s].indices.size();
  }
  std::string text;
  j = json::object();
  for (const auto& [c, n] : per) {
    char buf[96];
    std::snprintf(
        buf, sizeof(buf), "%s%s %zu (%.1f %%)", text.empty() ? "" : ", ", segmentation::toString(c), n.first,
        100.0 * static_cast<double>(n.second) / static_cast<double>(std::max<std::size_t>(points, 1)));
    text += buf;
    j[segmentation::toString(c)] = {{"segments", n.first}, {"points", n.second}};
  }
  return text;
}

}  // namespace segment_report
}  // namespace tools
}  // namespace pcl_ls3d
