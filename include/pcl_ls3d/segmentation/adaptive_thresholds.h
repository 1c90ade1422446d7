#pragma once
/// \file adaptive_thresholds.h
/// \brief The adaptive thresholds of IMRG (Wang et al. 2021 §3.1 and §3.2.2), in one place,
///        on top of the pcl_ls3d::stats helpers (median, Baarda data snooping, 1-D k-means).

#include <pcl_ls3d/segmentation/dimensionality_features.h>

#include <vector>

namespace pcl_ls3d {
namespace segmentation {

/// \brief v_t (§3.1): median plane-fit residual of the linear set (boundary and structure lines
///        resemble the planar set's boundary points). +inf (seed condition inactive) if the
///        linear set is empty.
double
seedResidualThreshold(const std::vector<PointFeatures>& features);

/// \brief d_t (§3.2.2, 1): Baarda backward elimination of large values over the nearest-segment
///        distances D (one-sided, significance \a alpha), then the maximum of what remains.
///        0 (no merging) for an empty sample.
double
distanceThreshold(const std::vector<double>& nearest_distances, double alpha);

/// \brief s_t (§3.2.2, 2): smallest gap between the \a centres k-means centres of the segment
///        residuals R_i. +inf if the residuals have a single distinct value (all alike).
double
similarityThreshold(const std::vector<double>& segment_residuals, int centres);

/// \brief V_t (§3.2.2, 3) from the candidate ΔV. ΔV is a ratio of volumes with a long right tail
///        and many exact zeros; on raw values the backward elimination eats the tail down to 0.
///        The snooping therefore runs on ∛ΔV (Wilson–Hilferty: the cube root of a gamma-like
///        positive variable is near-normal; it is also a ratio of length scales) and
///        V_t = (max kept)³. 0 for an empty sample.
double
volumeChangeThreshold(const std::vector<double>& volume_changes, double alpha);

}  // namespace segmentation
}  // namespace pcl_ls3d
