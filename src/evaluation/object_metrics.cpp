/// \file object_metrics.cpp
/// \brief The object-based rules of Wang et al. 2021 §4.1 (see object_metrics.h).

#include <pcl_ls3d/evaluation/object_metrics.h>
#include <pcl_ls3d/evaluation/segmentation_metrics.h>
#include <pcl_ls3d/stats/descriptive.h>

#include <algorithm>
#include <limits>
#include <unordered_map>

namespace pcl_ls3d {
namespace evaluation {
namespace {

/// The object a segment is valid for (more than half of its labelled points), its overlap
/// with it and its labelled size; object −1 if none.
struct SegmentMatch
{
  int object = -1;
  std::size_t overlap = 0, labelled = 0;
};

SegmentMatch
matchSegment(const pcl::PointIndices& seg, const ReferenceObjects& ref,
             std::unordered_map<int, std::size_t>& counts, std::vector<char>& seen)
{
  counts.clear();
  SegmentMatch m;
  for (const int i : seg.indices) {
    const auto p = static_cast<std::size_t>(i);
    if (seen[p])
      continue;  // a point listed twice counts once, for the first segment listing it
    seen[p] = 1;
    const int o = ref.object_of[p];
    if (o < 0)
      continue;
    ++m.labelled;
    ++counts[o];
  }
  for (const auto& [o, c] : counts)
    if (2 * c > m.labelled) {
      m.object = o;
      m.overlap = c;
    }
  return m;
}

double
medianOf(const std::vector<double>& v)
{
  return v.empty() ? std::numeric_limits<double>::quiet_NaN() : stats::median(v);
}

/// Every segment index names one of the n reference points (else `error` says which does not).
bool
indicesInRange(const std::vector<pcl::PointIndices>& segments, std::size_t n, std::string& error)
{
  for (std::size_t s = 0; s < segments.size(); ++s)
    for (const int i : segments[s].indices)
      if (i < 0 || static_cast<std::size_t>(i) >= n) {
        error = "segment " + std::to_string(s) + " holds index " + std::to_string(i) + " outside the " +
                std::to_string(n) + " reference points";
        return false;
      }
  return true;
}

/// Each segment's object, tallied on the objects (valid segments, matched points, largest
/// share, recognised).
std::vector<SegmentMatch>
matchSegments(const std::vector<pcl::PointIndices>& segments, const ReferenceObjects& ref,
              std::vector<ObjectResult>& objects)
{
  objects.resize(ref.objects());
  for (std::size_t o = 0; o < ref.objects(); ++o) {
    objects[o].group = ref.group_of_object[o];
    objects[o].points = ref.size[o];
  }
  std::vector<SegmentMatch> matches(segments.size());
  std::unordered_map<int, std::size_t> counts;
  std::vector<char> seen(ref.object_of.size(), 0);
  for (std::size_t s = 0; s < segments.size(); ++s) {
    matches[s] = matchSegment(segments[s], ref, counts, seen);
    if (matches[s].object < 0)
      continue;
    ObjectResult& o = objects[static_cast<std::size_t>(matches[s].object)];
    ++o.valid_segments;
    o.matched_points += matches[s].overlap;
    o.largest_share =
        std::max(o.largest_share, static_cast<double>(matches[s].overlap) / static_cast<double>(o.points));
  }
  for (auto& o : objects)
    o.recognised = 2 * o.matched_points > o.points;
  return matches;
}

/// Per class: objects, recognised, TP and FN points; of the large objects their valid segments
/// and largest shares (for the medians).
void
tallyClasses(const std::vector<ObjectResult>& objects, const ObjectEvaluationSettings& settings,
             std::vector<ObjectClassScores>& classes, std::vector<std::vector<double>>& valid,
             std::vector<std::vector<double>>& share)
{
  const std::size_t G = classes.size();
  for (const auto& o : objects) {
    if (o.group < 0 || static_cast<std::size_t>(o.group) >= G)
      continue;
    ObjectClassScores& c = classes[static_cast<std::size_t>(o.group)];
    ++c.objects;
    c.recognised += o.recognised;
    c.fn += o.recognised ? o.points - o.matched_points : o.points;
    if (o.recognised)
      c.tp += o.matched_points;
    if (o.points >= settings.min_object_points) {
      ++c.large_objects;
      valid[static_cast<std::size_t>(o.group)].push_back(static_cast<double>(o.valid_segments));
      share[static_cast<std::size_t>(o.group)].push_back(o.largest_share);
    }
  }
}

/// FP points: the labelled points of other objects in segments valid for a recognised object.
void
tallyFalsePositives(const std::vector<SegmentMatch>& matches, ObjectEvaluation& res)
{
  const std::size_t G = res.classes.size();
  for (const auto& m : matches) {
    if (m.object < 0 || !res.objects[static_cast<std::size_t>(m.object)].recognised)
      continue;
    const int g = res.objects[static_cast<std::size_t>(m.object)].group;
    if (g >= 0 && static_cast<std::size_t>(g) < G)
      res.classes[static_cast<std::size_t>(g)].fp += m.labelled - m.overlap;
  }
}

/// A class's precision, recall and F1 from its tallies, and its medians.
void
scoreClass(const std::vector<double>& valid, const std::vector<double>& share, ObjectClassScores& c)
{
  ClassScores s;
  s.tp = c.tp;
  s.fp = c.fp;
  s.fn = c.fn;
  computeScores(s);
  c.precision = s.precision;
  c.recall = s.recall;
  c.f1 = s.f1;
  c.median_valid_segments = medianOf(valid);
  c.median_largest_share = medianOf(share);
}

}  // namespace

bool
evaluateObjects(const std::vector<pcl::PointIndices>& segments, const ReferenceObjects& ref,
                const ObjectEvaluationSettings& settings, ObjectEvaluation& result, std::string& error)
{
  if (!indicesInRange(segments, ref.object_of.size(), error))
    return false;
  ObjectEvaluation res;
  res.method = result.method;
  res.seconds = result.seconds;
  res.segments = segments.size();
  const std::vector<SegmentMatch> matches = matchSegments(segments, ref, res.objects);
  const std::size_t G = ref.group_names.size();
  res.classes.resize(G);
  std::vector<std::vector<double>> valid(G), share(G);
  for (std::size_t g = 0; g < G; ++g)
    res.classes[g].name = ref.group_names[g];
  tallyClasses(res.objects, settings, res.classes, valid, share);
  tallyFalsePositives(matches, res);
  for (std::size_t g = 0; g < G; ++g)
    scoreClass(valid[g], share[g], res.classes[g]);
  result = std::move(res);
  return true;
}

}  // namespace evaluation
}  // namespace pcl_ls3d
