#pragma once
/// \file merge_state.h
/// \brief Internal: the working state of IMRG merging (contour points in one static kd-tree,
///        union-find over segments) and its geometric steps. Not installed API.

#include <pcl_ls3d/segmentation/segment_hull.h>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <algorithm>
#include <utility>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {
namespace detail {

constexpr int kNearestContourCandidates = 64;  ///< fallback k for the nearest other segment
constexpr double kInsideTolerance = 1e-6;      ///< [m] point-in-hull slack (float coordinates)

/// Working state of the merge loop (Fig. 8); segment ids are the initial labels.
struct MergeState
{
  std::vector<std::vector<int>> members;             ///< positions per initial segment
  std::vector<double> residual_sum;                  ///< Σ r_j over the (merged) segment
  std::vector<std::vector<int>> contour;             ///< global contour-point ids per root segment
  std::vector<double> volume;                        ///< hull volume per root segment
  std::vector<std::vector<Eigen::Vector4d>> planes;  ///< solid-hull facets per root segment
  std::vector<int> parent;                           ///< union-find
  std::vector<Eigen::Vector3f> contour_xyz;          ///< all initial contour points
  std::vector<int> contour_owner;                    ///< initial segment of each contour point
  std::vector<char> contour_active;                  ///< still a hull vertex of its (merged) segment
  std::size_t hull_kinds[5] = {0, 0, 0, 0, 0};       ///< initial hulls per HullKind
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;

  int
  find(int s)
  {
    while (parent[s] != s)
      s = parent[s] = parent[parent[s]];
    return s;
  }
  double
  meanResidual(int s) const
  {
    return residual_sum[s] / static_cast<double>(std::max<std::size_t>(1, members[s].size()));
  }
};

/// Hull of a set of global contour points; returns the surviving global ids and the volume.
SegmentHull
hullOfContour(const MergeState& st, const std::vector<int>& ids);

/// Nearest other live segment of root \a s within \a radius through active contour points.
/// Returns (segment, distance) or (−1, inf).
std::pair<int, double>
nearestSegment(MergeState& st, int s, double radius, const std::vector<char>& finished);

/// Nearest other segment before any merge (owners are the initial labels): 8 contour
/// neighbours first, 64 if none of those belongs to another segment. Read-only, thread-safe.
std::pair<int, double>
initialNearestSegment(const MergeState& st, int s);

/// ΔV = (V_j'' − V_j') / max(V_i, n_i·floor)  (eq. 2); also returns the merged hull. If S_i lies
/// inside the solid hull of S_j, the hull is unchanged and ΔV = 0 without calling qhull.
double
volumeChange(const MergeState& st, int i, int j, double floor, SegmentHull* merged);

/// Fill \a st: members and residual sums per segment, hulls (in parallel), contour kd-tree.
void
buildState(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
           const std::vector<float>& residuals, int n_segments, int threads, MergeState& st);

}  // namespace detail
}  // namespace segmentation
}  // namespace pcl_ls3d
