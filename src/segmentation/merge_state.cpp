/// \file merge_state.cpp
/// \brief Internal geometric steps of IMRG merging: contours, nearest segments, ΔV.

#include "merge_state.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl_ls3d {
namespace segmentation {
namespace detail {

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

/// Members, residual sums and hulls per segment, then one kd-tree over all contour points.
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
    ++st.hull_kinds[static_cast<int>(hulls[s].kind)];
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

}  // namespace detail
}  // namespace segmentation
}  // namespace pcl_ls3d
