#pragma once
/// \file segment_merging.h
/// \brief Segment merging of IMRG (Wang et al. 2021 §3.2, Fig. 8) with adaptive thresholds.

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {

/// \brief Which merge conditions apply.
enum class MergeRule
{
  None,                     ///< no merging
  DistanceOnly,             ///< MRG / strategy ① (Chen et al.): contour distance < d_t
  DistanceSimilarityVolume  ///< IMRG / strategy ②: distance, |R_i − R_j| < s_t, ΔV < V_t
};

/// \brief Merge settings; a negative threshold means "adaptive".
struct MergeSettings
{
  MergeRule rule = MergeRule::DistanceSimilarityVolume;
  double distance_threshold = -1.0;    ///< d_t [m]
  double similarity_threshold = -1.0;  ///< s_t [m]
  double volume_threshold = -1.0;      ///< V_t [-]
  double alpha = 0.001;                ///< significance of Baarda's w-test
  int kmeans_centres = 3;              ///< centres for s_t
  /// Volume per point [m³] for ΔV's denominator (see mergeSegments()); ≤ 0: spacing³ from the
  /// caller.
  double volume_floor = 0.0;
  int threads = 0;  ///< OpenMP threads for hulls and candidates (0: default)
};

/// \brief What mergeSegments() used and did.
struct MergeReport
{
  double distance_threshold = 0.0;    ///< d_t used
  double similarity_threshold = 0.0;  ///< s_t used
  double volume_threshold = 0.0;      ///< V_t used
  std::size_t segments_before = 0;
  std::size_t segments_after = 0;
  std::size_t merges = 0;
  std::size_t distance_samples = 0;  ///< |D| fed to the snooping
  std::size_t volume_samples = 0;    ///< |ΔV| fed to the snooping
  /// Hulls of the segments before merging by kind (segment_hull.h): degenerate segments
  /// (tiny, collinear, flat) are decided before qhull runs, and qhull runs silently.
  std::size_t hulls_tiny = 0, hulls_collinear = 0, hulls_flat = 0, hulls_solid = 0;
};

/// \brief Merge segments following Fig. 8.
///
/// S_i merges into its nearest unfinished segment S_j iff d ≤ d_t, |R_i − R_j| ≤ s_t and
/// ΔV ≤ V_t (Fig. 8 rejects on d > d_t or ΔR > s_t or ΔV > V_t); DistanceOnly tests d alone.
/// Adaptive thresholds (§3.2.2): d_t = max of D = {nearest contour distance per segment} kept by
/// Baarda backward elimination (one-sided, significance alpha, stats::dataSnooping); s_t =
/// smallest gap of 3 k-means centres of R_i (stats::kMeans1D; +inf if all R_i are alike);
/// V_t over the ΔV of nearest pairs passing d_t and s_t: the snooping runs on ∛ΔV
/// (Wilson–Hilferty; on raw ΔV, which has a long tail and many exact zeros, the backward
/// elimination eats the tail down to 0) and V_t = (max kept)³.
///
/// Contour points are convex-hull vertices (pcl::ConvexHull / qhull). Each segment is first
/// tested by PCA (λ of its covariance, relative to the largest): fewer than 4 points or a
/// collinear segment keeps all (≤ 3) points or its two extreme points as contour and has volume
/// 0; a numerically flat segment (λ3 ≤ 1e-9 λ1) gets a 2-D hull and volume 0; otherwise a 3-D
/// hull and its volume. In ΔV = (V_j'' − V_j')/V_i the denominator is max(V_i, n_i·floor)
/// (n_i points at spacing s occupy about n_i s³ even when their hull is flat), so merging two
/// coplanar flat pieces gives ΔV ≈ 0 (accepted) while a flat piece that adds real height to its
/// neighbour gives a large ΔV (rejected). A segment inside the other's solid hull has ΔV = 0.
/// Distances are minimal contour-to-contour distances; since the hull vertices of a union are
/// a subset of the union of hull vertices, one static kd-tree over the initial contour points
/// serves the whole loop. A segment whose nearest contour point of another segment is farther
/// than 64 contour neighbours away contributes no distance to D (isolated).
/// Order: smallest segment first, merged into its nearest unfinished segment (Fig. 8).
/// \param[in] points coordinates per position (local origin)
/// \param[in,out] labels segment id per position (−1 ignored); merged ids are relabelled dense
/// \param[in] residuals plane-fitting residual per position (R_i = mean over the segment, eq. 1)
/// \param[in] settings thresholds (negative = adaptive)
/// \param[in] volume_floor_default volume per point used when settings.volume_floor ≤ 0
MergeReport
mergeSegments(const std::vector<Eigen::Vector3f>& points, std::vector<int>& labels,
              const std::vector<float>& residuals, const MergeSettings& settings,
              double volume_floor_default);

}  // namespace segmentation
}  // namespace pcl_ls3d
