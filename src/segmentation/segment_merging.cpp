/// \file segment_merging.cpp
/// \brief IMRG segment merging (Wang et al. 2021 §3.2.1, Fig. 8) and the adaptive thresholds
///        of §3.2.2 (d_t, V_t: Baarda snooping; s_t: 3-centre k-means).

#include <pcl_ls3d/segmentation/segment_merging.h>

#include <pcl_ls3d/segmentation/adaptive_thresholds.h>
#include <pcl_ls3d/segmentation/segment_hull.h>

#include <pcl/common/time.h>
#include <pcl/console/print.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

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

constexpr int kNearestContourCandidates = 64;
constexpr double kInsideTolerance = 1e-6;  ///< [m] point-in-hull slack (float coordinates)

/// Working state of the merge loop (Fig. 8); segment ids are the initial labels.
struct MergeState
{
  std::vector<std::vector<int>> members;  ///< positions per initial segment
  std::vector<double> residual_sum;       ///< Σ r_j over the (merged) segment
  std::vector<std::vector<int>> contour;  ///< global contour-point ids per root segment
  std::vector<double> volume;             ///< hull volume per root segment
  std::vector<std::vector<Eigen::Vector4d>> planes;  ///< solid-hull facets per root segment
  std::vector<int> parent;                ///< union-find
  std::vector<Eigen::Vector3f> contour_xyz;  ///< all initial contour points
  std::vector<int> contour_owner;         ///< initial segment of each contour point
  std::vector<char> contour_active;       ///< still a hull vertex of its (merged) segment
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;

  int find(int s)
  {
    while (parent[s] != s)
      s = parent[s] = parent[parent[s]];
    return s;
  }
  double meanResidual(int s) const
  {
    return residual_sum[s] / static_cast<double>(std::max<std::size_t>(1, members[s].size()));
  }
};

/// Hull of a set of global contour points; returns the surviving global ids and the volume.
SegmentHull
hullOfContour(const MergeState& st, const std::vector<int>& ids)
{
  std::vector<Eigen::Vector3f> xyz(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
    xyz[i] = st.contour_xyz[ids[i]];
  SegmentHull h = computeSegmentHull(xyz);
  for (int& c : h.contour)
    c = ids[c];
  return h;
}

/// Nearest other live segment of root \a s within \a radius through active contour points.
/// Returns (segment, distance) or (−1, inf).
std::pair<int, double>
nearestSegment(MergeState& st, int s, double radius, const std::vector<char>& finished)
{
  std::pair<int, double> best{-1, std::numeric_limits<double>::infinity()};
  std::vector<int> idx;
  std::vector<float> d2;
  for (const int c : st.contour[s]) {
    pcl::PointXYZ q;
    q.getVector3fMap() = st.contour_xyz[c];
    st.tree.radiusSearch(q, radius, idx, d2);
    for (std::size_t t = 0; t < idx.size(); ++t) {
      if (!st.contour_active[idx[t]])
        continue;
      const int owner = st.find(st.contour_owner[idx[t]]);
      if (owner == s || finished[owner])
        continue;
      const double d = std::sqrt(static_cast<double>(d2[t]));
      if (d < best.second)
        best = {owner, d};
      break;  // results are sorted: the first valid one is the nearest for this query
    }
  }
  return best;
}

/// Nearest other segment before any merge (owners are the initial labels): 8 contour
/// neighbours first, 64 if none of those belongs to another segment. Read-only, thread-safe.
std::pair<int, double>
initialNearestSegment(const MergeState& st, int s)
{
  std::pair<int, double> best{-1, std::numeric_limits<double>::infinity()};
  std::vector<int> idx;
  std::vector<float> d2;
  const int n_contour = static_cast<int>(st.contour_xyz.size());
  for (const int k : {8, kNearestContourCandidates}) {
    for (const int c : st.contour[s]) {
      pcl::PointXYZ q;
      q.getVector3fMap() = st.contour_xyz[c];
      st.tree.nearestKSearch(q, std::min(k, n_contour), idx, d2);
      for (std::size_t t = 0; t < idx.size(); ++t) {
        if (st.contour_owner[idx[t]] == s)
          continue;
        const double d = std::sqrt(static_cast<double>(d2[t]));
        if (d < best.second)
          best = {st.contour_owner[idx[t]], d};
        break;
      }
    }
    if (best.first >= 0 || k >= n_contour)
      break;
  }
  return best;
}

/// ΔV = (V_j'' − V_j') / max(V_i, n_i·floor)  (eq. 2); also returns the merged hull. If S_i lies
/// inside the solid hull of S_j, the hull is unchanged and ΔV = 0 without calling qhull.
double
volumeChange(const MergeState& st, int i, int j, double floor, SegmentHull* merged)
{
  if (!st.planes[j].empty()) {
    SegmentHull hj;
    hj.kind = HullKind::Solid;
    hj.planes = st.planes[j];
    std::vector<Eigen::Vector3f> xi;
    for (const int c : st.contour[i])
      xi.push_back(st.contour_xyz[c]);
    if (insideHull(hj, xi, kInsideTolerance)) {
      if (merged) {
        merged->kind = HullKind::Solid;
        merged->contour = st.contour[j];
        merged->volume = st.volume[j];
        merged->planes = std::move(hj.planes);
      }
      return 0.0;
    }
  }
  std::vector<int> ids = st.contour[j];
  ids.insert(ids.end(), st.contour[i].begin(), st.contour[i].end());
  SegmentHull h = hullOfContour(st, ids);
  // A flat or tiny S_i has no hull volume; n_i points at spacing s still occupy ~n_i s³.
  const double vi = std::max(st.volume[i], floor * static_cast<double>(st.members[i].size()));
  const double dv = (h.volume - st.volume[j]) / vi;
  if (merged)
    *merged = std::move(h);
  return std::max(0.0, dv);
}

void
buildState(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
           const std::vector<float>& residuals, int n_segments, int threads, MergeState& st)
{
  st.members.assign(n_segments, {});
  st.residual_sum.assign(n_segments, 0.0);
  for (std::size_t p = 0; p < labels.size(); ++p) {
    if (labels[p] < 0)
      continue;
    st.members[labels[p]].push_back(static_cast<int>(p));
    st.residual_sum[labels[p]] += residuals[p];
  }
  st.contour.assign(n_segments, {});
  st.volume.assign(n_segments, 0.0);
  st.parent.resize(n_segments);
  std::iota(st.parent.begin(), st.parent.end(), 0);
  std::vector<SegmentHull> hulls(n_segments);
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
  for (int s = 0; s < n_segments; ++s) {
    std::vector<Eigen::Vector3f> xyz;
    xyz.reserve(st.members[s].size());
    for (const int p : st.members[s])
      xyz.push_back(points[p]);
    hulls[s] = computeSegmentHull(xyz);
  }
  st.planes.assign(n_segments, {});
  for (int s = 0; s < n_segments; ++s) {
    st.volume[s] = hulls[s].volume;
    st.planes[s] = std::move(hulls[s].planes);
    for (const int c : hulls[s].contour) {
      st.contour[s].push_back(static_cast<int>(st.contour_xyz.size()));
      st.contour_xyz.push_back(points[st.members[s][c]]);
      st.contour_owner.push_back(s);
    }
  }
  st.contour_active.assign(st.contour_xyz.size(), 1);
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(st.contour_xyz.size());
  for (std::size_t c = 0; c < st.contour_xyz.size(); ++c)
    (*cloud)[c].getVector3fMap() = st.contour_xyz[c];
  if (!cloud->empty())
    st.tree.setInputCloud(cloud);
}

}  // namespace

MergeReport
mergeSegments(const std::vector<Eigen::Vector3f>& points, std::vector<int>& labels,
              const std::vector<float>& residuals, const MergeSettings& settings,
              double volume_floor_default)
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
  const double floor = settings.volume_floor > 0.0 ? settings.volume_floor
                                                   : std::max(volume_floor_default, 1e-12);

  MergeState st;
  pcl::StopWatch watch;
  buildState(points, labels, residuals, n_segments, threads, st);
  const double t_hulls = watch.getTimeSeconds();

  // Nearest neighbour segment of every segment: the sample D (§3.2.2, 1).
  std::vector<std::pair<int, double>> nearest(n_segments);
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads)
  for (int s = 0; s < n_segments; ++s)
    nearest[s] = initialNearestSegment(st, s);
  std::vector<double> D;
  for (int s = 0; s < n_segments; ++s)
    if (nearest[s].first >= 0)
      D.push_back(nearest[s].second);
  rep.distance_samples = D.size();
  const double t_nearest = watch.getTimeSeconds();
  rep.distance_threshold = settings.distance_threshold >= 0.0
                               ? settings.distance_threshold
                               : distanceThreshold(D, settings.alpha);

  // s_t: smallest gap between 3 k-means centres of the segment residuals R_i (eq. 1).
  rep.similarity_threshold = std::numeric_limits<double>::infinity();
  if (full) {
    if (settings.similarity_threshold >= 0.0) {
      rep.similarity_threshold = settings.similarity_threshold;
    } else {
      std::vector<double> R(n_segments);
      for (int s = 0; s < n_segments; ++s)
        R[s] = st.meanResidual(s);
      rep.similarity_threshold = similarityThreshold(R, settings.kmeans_centres);
    }
  }

  // ΔV of segment s into its initial nearest segment (−1: not a candidate); reused by the loop
  // while neither segment has changed.
  std::vector<double> candidate_dv(n_segments, -1.0);
  // V_t: ΔV over the nearest pairs that pass d_t and s_t, smaller segment into larger.
  rep.volume_threshold = std::numeric_limits<double>::infinity();
  if (full) {
    if (settings.volume_threshold >= 0.0) {
      rep.volume_threshold = settings.volume_threshold;
    } else {
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
      for (int s = 0; s < n_segments; ++s) {
        const int j = nearest[s].first;
        if (j < 0 || nearest[s].second > rep.distance_threshold ||
            std::abs(st.meanResidual(s) - st.meanResidual(j)) > rep.similarity_threshold)
          continue;
        // Smaller into larger, in the order the merge loop will visit the pair.
        const bool s_first = st.members[s].size() < st.members[j].size() ||
                             (st.members[s].size() == st.members[j].size() && s < j);
        candidate_dv[s] = s_first ? volumeChange(st, s, j, floor, nullptr)
                                  : volumeChange(st, j, s, floor, nullptr);
      }
      std::vector<double> dV;
      for (int s = 0; s < n_segments; ++s)
        if (candidate_dv[s] >= 0.0)
          dV.push_back(candidate_dv[s]);
      rep.volume_samples = dV.size();
      rep.volume_threshold = volumeChangeThreshold(dV, settings.alpha);
    }
  }

  const double t_thresholds = watch.getTimeSeconds();
  // Fig. 8: smallest segment first; merge into its nearest unfinished segment or finish it.
  std::vector<int> order(n_segments);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return st.members[a].size() < st.members[b].size();
  });
  std::vector<char> finished(n_segments, 0);
  std::vector<char> changed(n_segments, 0);  // hull differs from the initial one
  for (const int s : order) {
    finished[s] = 1;  // S_1 leaves S_u whatever happens
    const auto [j, d] = nearestSegment(st, s, rep.distance_threshold, finished);
    if (j < 0 || d > rep.distance_threshold)
      continue;
    SegmentHull merged;
    if (full) {
      if (std::abs(st.meanResidual(s) - st.meanResidual(j)) > rep.similarity_threshold)
        continue;
      const bool unchanged = !changed[s] && !changed[j] && nearest[s].first == j;
      if (unchanged && candidate_dv[s] > rep.volume_threshold)
        continue;  // same pair, same hulls as in the threshold stage: ΔV already known
      if (volumeChange(st, s, j, floor, &merged) > rep.volume_threshold)
        continue;
    } else {
      std::vector<int> ids = st.contour[j];
      ids.insert(ids.end(), st.contour[s].begin(), st.contour[s].end());
      merged = hullOfContour(st, ids);
    }
    // Merge S_1 into S_j: union-find, members, residual sum, new hull H_j (Fig. 8).
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
    changed[j] = 1;
    ++rep.merges;
  }

  PCL_DEBUG("[pcl_ls3d::segmentation::mergeSegments] hulls %.2f s, nearest %.2f s, "
            "thresholds %.2f s, loop %.2f s; %zu contour points.\n", t_hulls,
            t_nearest - t_hulls, t_thresholds - t_nearest, watch.getTimeSeconds() - t_thresholds,
            st.contour_xyz.size());
  // Dense relabelling of the roots.
  std::vector<int> dense(n_segments, -1);
  int next = 0;
  for (int& l : labels) {
    if (l < 0)
      continue;
    const int root = st.find(l);
    if (dense[root] < 0)
      dense[root] = next++;
    l = dense[root];
  }
  rep.segments_after = static_cast<std::size_t>(next);
  return rep;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
