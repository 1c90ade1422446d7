/// \file segment_merging.cpp
/// \brief IMRG segment merging (Wang et al. 2021 §3.2.1, Fig. 8) and the adaptive thresholds
///        of §3.2.2 (d_t, V_t: Baarda snooping; s_t: 3-centre k-means).

#include <pcl_ls3d/segmentation/segment_merging.h>

#include <pcl_ls3d/segmentation/adaptive_thresholds.h>
#include <pcl_ls3d/segmentation/segment_hull.h>

#include "merge_state.h"

#include <pcl/common/time.h>
#include <pcl/console/print.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl_ls3d {
namespace segmentation {
namespace {

using detail::MergeState;

/// The nearest segment of every segment (§3.2.2, 1), and its distances: the sample D of d_t.
std::vector<std::pair<int, double>>
nearestSegments(const MergeState& st, int n_segments, int threads, std::vector<double>& D)
{
  std::vector<std::pair<int, double>> nearest(static_cast<std::size_t>(n_segments));
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads)
  for (int s = 0; s < n_segments; ++s)
    nearest[s] = detail::initialNearestSegment(st, s);
  D.clear();
  for (int s = 0; s < n_segments; ++s)
    if (nearest[s].first >= 0)
      D.push_back(nearest[s].second);
  return nearest;
}

/// s_t: the smallest gap between 3 k-means centres of the segment residuals R_i (eq. 1).
double
chooseSimilarityThreshold(const MergeState& st, int n_segments, const MergeSettings& settings)
{
  if (settings.similarity_threshold >= 0.0)
    return settings.similarity_threshold;
  std::vector<double> R(static_cast<std::size_t>(n_segments));
  for (int s = 0; s < n_segments; ++s)
    R[s] = st.meanResidual(s);
  return similarityThreshold(R, settings.kmeans_centres);
}

/// V_t (given, or from ΔV over the nearest pairs that pass d_t and s_t, smaller segment into
/// larger, in the order the merge loop will visit them); also fills rep.volume_samples, and
/// \a candidate_dv keeps each ΔV (−1: no candidate) for the loop to reuse while neither
/// segment has changed.
double
chooseVolumeThreshold(const MergeState& st, const std::vector<std::pair<int, double>>& nearest,
                      const MergeSettings& settings, double floor, int threads, MergeReport& rep,
                      std::vector<double>& candidate_dv)
{
  if (settings.volume_threshold >= 0.0)
    return settings.volume_threshold;
  const int n_segments = static_cast<int>(nearest.size());
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
  for (int s = 0; s < n_segments; ++s) {
    const int j = nearest[s].first;
    if (j < 0 || nearest[s].second > rep.distance_threshold ||
        std::abs(st.meanResidual(s) - st.meanResidual(j)) > rep.similarity_threshold)
      continue;
    const bool s_first = st.members[s].size() < st.members[j].size() ||
                         (st.members[s].size() == st.members[j].size() && s < j);
    candidate_dv[s] = s_first ? detail::volumeChange(st, s, j, floor, nullptr)
                              : detail::volumeChange(st, j, s, floor, nullptr);
  }
  std::vector<double> dV;
  for (int s = 0; s < n_segments; ++s)
    if (candidate_dv[s] >= 0.0)
      dV.push_back(candidate_dv[s]);
  rep.volume_samples = dV.size();
  return volumeChangeThreshold(dV, settings.alpha);
}

/// Merges S_s into S_j (Fig. 8): union-find, members, residual sum, the new hull H_j (its
/// planes are moved out of \a merged).
void
mergeInto(MergeState& st, int s, int j, SegmentHull& merged)
{
  st.parent[s] = j;
  st.residual_sum[j] += st.residual_sum[s];
  st.members[j].insert(st.members[j].end(), st.members[s].begin(), st.members[s].end());
  st.members[s].clear();
  for (const int c : st.contour[j])
    st.contour_active[c] = 0;
  for (const int c : st.contour[s])
    st.contour_active[c] = 0;
  for (const int c : merged.contour)
    st.contour_active[c] = 1;
  st.contour[j] = merged.contour;
  st.contour[s].clear();
  st.volume[j] = merged.volume;
  st.planes[j] = std::move(merged.planes);
  st.planes[s].clear();
}

/// Labels of the merged segments' roots, dense from 0; returns their number.
std::size_t
relabelRoots(MergeState& st, int n_segments, std::vector<int>& labels)
{
  std::vector<int> dense(static_cast<std::size_t>(n_segments), -1);
  int next = 0;
  for (int& l : labels) {
    if (l < 0)
      continue;
    const int root = st.find(l);
    if (dense[root] < 0)
      dense[root] = next++;
    l = dense[root];
  }
  return static_cast<std::size_t>(next);
}

/// How many initial hulls are of each kind.
void
recordHullKinds(const MergeState& st, MergeReport& rep)
{
  rep.hulls_tiny = st.hull_kinds[static_cast<int>(HullKind::Tiny)];
  rep.hulls_collinear = st.hull_kinds[static_cast<int>(HullKind::Collinear)];
  rep.hulls_flat = st.hull_kinds[static_cast<int>(HullKind::Flat)];
  rep.hulls_solid = st.hull_kinds[static_cast<int>(HullKind::Solid)];
}

/// The merge loop's inputs: the state, the thresholds' stage and the rule.
struct MergeLoop
{
  MergeState& st;
  const std::vector<std::pair<int, double>>& nearest;  // each segment's initial nearest segment
  const std::vector<double>& candidate_dv;             // its ΔV from the threshold stage (−1: none)
  bool full;                                           // distance, similarity and volume rules
  double floor;                                        // the volume floor of ΔV
  MergeReport& rep;
  std::vector<char> changed;  // hull differs from the initial one
};

/// Does S_s merge into its nearest segment S_j under the full rule (s_t, then V_t)? Then
/// \a merged holds the union's hull.
bool
passesSimilarityAndVolume(const MergeLoop& L, int s, int j, SegmentHull& merged)
{
  const MergeState& st = L.st;
  if (std::abs(st.meanResidual(s) - st.meanResidual(j)) > L.rep.similarity_threshold)
    return false;
  const bool unchanged = !L.changed[s] && !L.changed[j] && L.nearest[s].first == j;
  if (unchanged && L.candidate_dv[s] > L.rep.volume_threshold)
    return false;  // same pair, same hulls as in the threshold stage: ΔV already known
  return !(detail::volumeChange(st, s, j, L.floor, &merged) > L.rep.volume_threshold);
}

/// Fig. 8: smallest segment first; merge into its nearest unfinished segment or finish it.
void
runMergeLoop(MergeLoop& L, int n_segments)
{
  MergeState& st = L.st;
  std::vector<int> order(n_segments);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return st.members[a].size() < st.members[b].size(); });
  std::vector<char> finished(n_segments, 0);
  L.changed.assign(n_segments, 0);
  for (const int s : order) {
    finished[s] = 1;  // S_1 leaves S_u whatever happens
    const auto [j, d] = detail::nearestSegment(st, s, L.rep.distance_threshold, finished);
    if (j < 0 || d > L.rep.distance_threshold)
      continue;
    SegmentHull merged;
    if (L.full) {
      if (!passesSimilarityAndVolume(L, s, j, merged))
        continue;
    } else {
      std::vector<int> ids = st.contour[j];
      ids.insert(ids.end(), st.contour[s].begin(), st.contour[s].end());
      merged = detail::hullOfContour(st, ids);
    }
    mergeInto(st, s, j, merged);
    L.changed[j] = 1;
    ++L.rep.merges;
  }
}

}  // namespace

MergeReport
mergeSegments(const std::vector<Eigen::Vector3f>& points, std::vector<int>& labels,
              const std::vector<float>& residuals, const MergeSettings& settings, double volume_floor_default)
{
  MergeReport rep;
  const int n_segments = labels.empty() ? 0 : *std::max_element(labels.begin(), labels.end()) + 1;
  rep.segments_before = rep.segments_after = static_cast<std::size_t>(std::max(0, n_segments));
  if (settings.rule == MergeRule::None || n_segments < 2 || points.size() != labels.size() ||
      residuals.size() != labels.size())
    return rep;
  const bool full = settings.rule == MergeRule::DistanceSimilarityVolume;
#ifdef _OPENMP
  const int threads = settings.threads > 0 ? settings.threads : omp_get_max_threads();
#else
  const int threads = 1;
#endif
  const double floor =
      settings.volume_floor > 0.0 ? settings.volume_floor : std::max(volume_floor_default, 1e-12);

  MergeState st;
  pcl::StopWatch watch;
  detail::buildState(points, labels, residuals, n_segments, threads, st);
  const double t_hulls = watch.getTimeSeconds();
  recordHullKinds(st, rep);

  std::vector<double> D;
  const std::vector<std::pair<int, double>> nearest = nearestSegments(st, n_segments, threads, D);
  rep.distance_samples = D.size();
  const double t_nearest = watch.getTimeSeconds();
  rep.distance_threshold =
      settings.distance_threshold >= 0.0 ? settings.distance_threshold : distanceThreshold(D, settings.alpha);
  const double inf = std::numeric_limits<double>::infinity();
  rep.similarity_threshold = full ? chooseSimilarityThreshold(st, n_segments, settings) : inf;
  std::vector<double> candidate_dv(static_cast<std::size_t>(n_segments), -1.0);
  rep.volume_threshold =
      full ? chooseVolumeThreshold(st, nearest, settings, floor, threads, rep, candidate_dv) : inf;

  const double t_thresholds = watch.getTimeSeconds();
  MergeLoop loop{st, nearest, candidate_dv, full, floor, rep, {}};
  runMergeLoop(loop, n_segments);
  PCL_DEBUG("[pcl_ls3d::segmentation::mergeSegments] hulls %.2f s, nearest %.2f s, "
            "thresholds %.2f s, loop %.2f s; %zu contour points.\n",
            t_hulls, t_nearest - t_hulls, t_thresholds - t_nearest, watch.getTimeSeconds() - t_thresholds,
            st.contour_xyz.size());
  rep.segments_after = relabelRoots(st, n_segments, labels);
  return rep;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
