#include <pcl_ls3d/evaluation/segmentation_metrics.h>

#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace evaluation {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Column of the confusion matrix a segment's points go to: its majority group
/// (ties: lower index; "other" = G loses ties against named groups), or -1 if no evaluated point.
int
majorityGroup(const pcl::PointIndices& seg, const std::vector<int>& ref_group, std::size_t G)
{
  std::vector<std::size_t> votes(G + 1, 0);
  std::size_t n = 0;
  for (int idx : seg.indices) {
    const int g = ref_group[static_cast<std::size_t>(idx)];
    if (g == ClassLookup::kExcluded)
      continue;
    ++votes[g == ClassLookup::kOther ? G : static_cast<std::size_t>(g)];
    ++n;
  }
  if (n == 0)
    return -1;
  std::size_t best = 0;
  for (std::size_t g = 1; g <= G; ++g)
    if (votes[g] > votes[best])
      best = g;
  return static_cast<int>(best);
}
/// Per group (and "other") from res.confusion: TP = diagonal; FP = rest of the column; FN =
/// rest of the row (including "none").
void
scoreConfusion(const std::vector<ClassGroup>& groups, const std::vector<std::size_t>& segs_per_col,
               SegmentationEvaluation& res)
{
  const std::size_t G = groups.size();
  auto scoresOf = [&](std::size_t g, const std::string& name) {
    ClassScores s;
    s.name = name;
    s.segments = segs_per_col.empty() ? 0 : segs_per_col[g];
    for (std::size_t c = 0; c < G + 2; ++c)
      s.reference_points += res.confusion[g][c];
    for (std::size_t r = 0; r < G + 1; ++r)
      s.predicted_points += res.confusion[r][g];
    s.tp = res.confusion[g][g];
    s.fp = s.predicted_points - s.tp;
    s.fn = s.reference_points - s.tp;
    computeScores(s);
    return s;
  };
  res.classes.clear();
  for (std::size_t g = 0; g < G; ++g)
    res.classes.push_back(scoresOf(g, groups[g].name));
  res.other = scoresOf(G, "other");
}

/// Every segment index names one of the n reference labels (else `error` says which does not).
bool
indicesInRange(const std::vector<pcl::PointIndices>& segments, std::size_t n, std::string& error)
{
  for (std::size_t s = 0; s < segments.size(); ++s)
    for (int idx : segments[s].indices)
      if (idx < 0 || static_cast<std::size_t>(idx) >= n) {
        error = "segment " + std::to_string(s) + " holds index " + std::to_string(idx) + " outside the " +
                std::to_string(n) + " reference labels";
        return false;
      }
  return true;
}

/// Predicted column per point: its first segment's majority group, G + 1 ("none") until a
/// segment claims it; counts the segments per column and the evaluation's segment figures.
std::vector<int>
predictedColumns(const std::vector<pcl::PointIndices>& segments, const std::vector<int>& ref_group,
                 std::size_t G, std::size_t min_segment_size, std::vector<std::size_t>& segs_per_col,
                 SegmentationEvaluation& res)
{
  const std::size_t n = ref_group.size();
  std::vector<int> predicted(n, static_cast<int>(G) + 1);
  std::vector<char> claimed(n, 0);
  segs_per_col.assign(G + 1, 0);
  for (const auto& seg : segments) {
    if (seg.indices.size() < min_segment_size) {
      ++res.segments_too_small;
      continue;
    }
    const int col = majorityGroup(seg, ref_group, G);
    if (col >= 0) {
      ++res.segments_evaluated;
      ++segs_per_col[static_cast<std::size_t>(col)];
    }
    for (int idx : seg.indices) {
      const auto i = static_cast<std::size_t>(idx);
      if (claimed[i]) {
        ++res.points_duplicated;
        continue;
      }
      claimed[i] = 1;
      if (col >= 0)
        predicted[i] = col;
    }
  }
  return predicted;
}

/// The confusion matrix (rows: reference groups and "other"; columns: those, then "none") of
/// the evaluated points.
void
fillConfusion(const std::vector<int>& ref_group, const std::vector<int>& predicted, std::size_t G,
              SegmentationEvaluation& res)
{
  const int none = static_cast<int>(G) + 1;
  res.confusion.assign(G + 1, std::vector<std::size_t>(G + 2, 0));
  for (std::size_t i = 0; i < ref_group.size(); ++i) {
    if (ref_group[i] == ClassLookup::kExcluded)
      continue;
    const std::size_t r = ref_group[i] == ClassLookup::kOther ? G : static_cast<std::size_t>(ref_group[i]);
    ++res.confusion[r][static_cast<std::size_t>(predicted[i])];
    if (predicted[i] == none)
      ++res.points_unsegmented;
  }
}

}  // namespace

void
computeScores(ClassScores& s)
{
  const auto tp = static_cast<double>(s.tp), fp = static_cast<double>(s.fp), fn = static_cast<double>(s.fn);
  s.precision = (s.tp + s.fp) > 0 ? tp / (tp + fp) : kNaN;
  s.recall = (s.tp + s.fn) > 0 ? tp / (tp + fn) : kNaN;
  // 2PR/(P+R) = 2TP/(2TP+FP+FN): defined (0) even when P or R is undefined but the other is 0.
  s.f1 = (s.tp + s.fp + s.fn) > 0 ? 2.0 * tp / (2.0 * tp + fp + fn) : kNaN;
}

bool
evaluateSegmentation(const std::vector<pcl::PointIndices>& segments, const std::vector<int>& reference_labels,
                     const SegmentationEvaluationSettings& settings, SegmentationEvaluation& result,
                     std::string& error)
{
  const std::size_t n = reference_labels.size();
  const std::size_t G = settings.groups.size();
  if (!indicesInRange(segments, n, error))
    return false;
  SegmentationEvaluation res;
  res.method = result.method;
  res.seconds = result.seconds;
  res.segments = segments.size();
  res.points_total = n;
  const ClassLookup lookup(settings.groups, settings.excluded_codes);
  std::vector<int> ref_group(n);
  for (std::size_t i = 0; i < n; ++i) {
    ref_group[i] = lookup.groupOf(reference_labels[i]);
    if (ref_group[i] != ClassLookup::kExcluded)
      ++res.points_evaluated;
  }
  std::vector<std::size_t> segs_per_col;
  const std::vector<int> predicted =
      predictedColumns(segments, ref_group, G, settings.min_segment_size, segs_per_col, res);
  fillConfusion(ref_group, predicted, G, res);
  scoreConfusion(settings.groups, segs_per_col, res);
  result = std::move(res);
  return true;
}

bool
evaluateClassification(const std::vector<int>& predicted_codes, const std::vector<int>& reference_labels,
                       const SegmentationEvaluationSettings& settings, SegmentationEvaluation& result,
                       std::string& error)
{
  const std::size_t n = reference_labels.size();
  if (predicted_codes.size() != n) {
    error = std::to_string(predicted_codes.size()) + " predicted classes for " + std::to_string(n) +
            " reference labels";
    return false;
  }
  const std::size_t G = settings.groups.size();
  SegmentationEvaluation res;
  res.method = result.method;
  res.seconds = result.seconds;
  res.segments = result.segments;
  res.points_total = n;
  const ClassLookup lookup(settings.groups, settings.excluded_codes);
  res.confusion.assign(G + 1, std::vector<std::size_t>(G + 2, 0));
  for (std::size_t i = 0; i < n; ++i) {
    const int ref = lookup.groupOf(reference_labels[i]);
    if (ref == ClassLookup::kExcluded)
      continue;
    ++res.points_evaluated;
    // 0 (no segment) and 1 (unclassified) predict nothing, whatever the groups name.
    const int pred = predicted_codes[i] <= 1 ? ClassLookup::kExcluded : lookup.groupOf(predicted_codes[i]);
    const std::size_t col = pred == ClassLookup::kExcluded ? G + 1
                            : pred == ClassLookup::kOther  ? G
                                                           : static_cast<std::size_t>(pred);
    res.points_unsegmented += col == G + 1;
    ++res.confusion[ref == ClassLookup::kOther ? G : static_cast<std::size_t>(ref)][col];
  }
  scoreConfusion(settings.groups, {}, res);
  result = std::move(res);
  return true;
}

}  // namespace evaluation
}  // namespace pcl_ls3d
