#pragma once
/// \file stable_refinement.h
/// \brief Stable-part refinement (beyond Li et al. 2001): a robust estimator still gives a
///        deformation of a few σ part of its weight (Tukey's c = 4.685 σ̂ keeps 35 % at 3 σ), and
///        that pull is what makes small magnitudes fail (Li's Table 5: 3–4 σ needed at 9–25 %).
///        Local deformation is gathered in patches (Li: "the deformation is gathered in one
///        area"), which the point-wise weights cannot use and the regions can: the regions of
///        the neighbourhood-mean test (LOD95, residual_field.h) and their rim within the link
///        distance are left out, and the rest is matched again with the M-estimator from the
///        robust estimate. Repeated while the left-out set changes. When the regions cover more
///        than `max_left_out` of the surface, only the largest of them are left out. PCL-free.

#include <pcl_ls3d/deformation/deformation_regions.h>
#include <pcl_ls3d/deformation/residual_field.h>
#include <pcl_ls3d/estimators/robust_matching.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace deformation {

/// \brief Settings of refineOnStablePart().
struct StableRefinementSettings
{
  int max_rounds = 10;  ///< a cap: the rounds stop when the left-out set repeats; 0: off
  /// Stop (keep the robust estimate) when the left-out points exceed this share of the observed
  /// ones: the regions are then not a minority, and the remainder no surer a stable part.
  double max_left_out = 0.5;

  bool
  isValid(std::string* why = nullptr) const;
};

/// The matching of a stable part: the M-estimator (Tukey, c = 4.685, MAD scale) from the robust
/// estimate — on a stable part 95 % efficient, and it still down-weights what the regions missed.
RobustMatchingSettings
stablePartMatching(const RobustMatchingSettings& robust);

/// A matching of the stable part keeps what the robust one found in its high-breakdown stage
/// (start, search, subsets, scales, block start) and adds its iterations.
void
keepHighBreakdownFigures(const RobustMatchingReport& robust, RobustMatchingReport& refined);

/// \brief The points i with keep(i), and their indices in the caller's cloud (point_indices[i],
///        or i when point_indices is empty) — the part a stable-part matching runs on.
template <typename Keep>
void
selectPoints(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& point_indices, Keep keep,
             std::vector<Eigen::Vector3d>& selected, std::vector<int>& selected_indices)
{
  selected.clear();
  selected_indices.clear();
  for (std::size_t i = 0; i < points.size(); ++i)
    if (keep(i)) {
      selected.push_back(points[i]);
      selected_indices.push_back(point_indices.empty() ? static_cast<int>(i) : point_indices[i]);
    }
}

/// Per point: 1 when it belongs to a region (id > 0) or lies within `analysis.adjacency` of a
/// region point (in the plane `plane_axis` when ≥ 0, else in 3-D), else 0. Noise clusters are
/// not left out: isolated detections are what the noise of a stable surface produces.
std::vector<std::uint8_t>
nearRegions(const std::vector<Eigen::Vector3d>& points, const RegionAnalysis& analysis, int plane_axis);

/// \brief What refineOnStablePart() did.
struct StableRefinementReport
{
  int rounds = 0;            ///< matchings of the stable part that were kept
  std::size_t left_out = 0;  ///< points left out in the last kept round
  std::string stopped;       ///< why it stopped ("no region", "unchanged", ...)
};

/// Refines `robust` (the robust matching of `points` onto `reference`) on its stable part.
/// \param[in] points the matching's epoch points (epoch coordinates; NaN allowed)
/// \param[in] point_indices the caller's index of each point (empty: 0..n−1)
/// \param[in] matching the settings `robust` was made with (adjustment, rule parameters)
/// \param[in] residuals, regions how the field and its regions are found each round (the
///            detection rule is always LOD95 here; k, the reach and the region rules are these)
/// \param[in,out] robust replaced by the refined matching when a round succeeded (the
///            high-breakdown fields and the subset counts are kept)
StableRefinementReport
refineOnStablePart(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& point_indices,
                   const TargetSurface& reference, const ConjugateRule& rule,
                   const RobustMatchingSettings& matching, const ResidualSettings& residuals,
                   const RegionSettings& regions, const StableRefinementSettings& settings,
                   RobustMatchingReport& robust);

}  // namespace deformation
}  // namespace pcl_ls3d
