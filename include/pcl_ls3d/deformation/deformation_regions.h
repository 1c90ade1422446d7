#pragma once
/// \file deformation_regions.h
/// \brief Connected regions of significant residuals of one sign (uplift / subsidence), their
///        size, displacement and volume, and the share of the surface that changed. PCL-free.
///
/// Two significant points of the same sign are connected when they lie within `adjacency` of
/// each other (default 2.5 × the epoch's point spacing s, cloudSpacing()). Regions with fewer
/// than `min_points` points are isolated detections — noise, as Li et al. (2001) note, "easily
/// filtered out" — and are reported apart. Areas count occupied cells of edge s on the epoch's
/// dominant plane (xy for terrain); a region's volume is Σ over its cells of the mean residual
/// × s² (a volume change when the residuals are perpendicular to that plane, e.g. LZD heights).

#include <pcl_ls3d/deformation/residual_field.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_ls3d {
namespace deformation {

/// \brief Settings of the region analysis.
struct RegionSettings
{
  std::size_t min_points = 10;  ///< smaller connected sets are noise
  /// Hysteresis (Canny 1986): a region grows into adjacent points of its sign with
  /// |r| > grow_k σ_i (weaker than the significance test), from point to point, so a deformed
  /// patch is not cut at its low tail. 0: off. Only points next to a region of ≥ min_points
  /// significant points join; an isolated weak point never does. Default 2 (set before any
  /// measurement; at 5 σ it lifts the recall from 0.87 to 0.96, docs/BENCHMARKS.md).
  double grow_k = 2.0;
  double adjacency = 0.0;  ///< link distance; 0: 2.5 × the point spacing
  double cell = 0.0;       ///< area cell edge; 0: the point spacing
  /// Normal axis of the plane areas are counted on (0 x, 1 y, 2 z); −1: the largest projection
  /// of the epoch's box, points linked in 3-D. When set (≥ 0), points are also linked in that
  /// plane. analyseDeformation() sets 2 (xy) for the LZD rule.
  int plane_axis = -1;

  bool
  isValid(std::string* why = nullptr) const;
};

/// \brief One connected region (or one noise cluster).
struct DeformationRegion
{
  int id = 0;    ///< 1, 2, ... by decreasing area (noise: −1)
  int sign = 1;  ///< +1 the epoch is above / outside the reference, −1 below
  std::size_t points = 0;
  double area = 0.0;                                   ///< [length²]
  double mean = 0.0, max = 0.0, min = 0.0;             ///< of the residuals [length]
  double volume = 0.0;                                 ///< [length³], signed
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< epoch coordinates
  Eigen::Vector3d box_min = Eigen::Vector3d::Zero(), box_max = Eigen::Vector3d::Zero();
};

/// \brief Regions of a residual field.
struct RegionAnalysis
{
  std::vector<int> region;                 ///< per point: region id (> 0), −1 noise, 0 none
  std::vector<DeformationRegion> regions;  ///< by decreasing area
  std::vector<DeformationRegion> noise;    ///< clusters below min_points
  double area_observed = 0.0;              ///< cells with at least one residual
  double area_deformed = 0.0;              ///< cells of the regions
  double percent_deformed = 0.0;           ///< 100 · area_deformed / area_observed
  double spacing = 0.0, adjacency = 0.0, cell = 0.0;
  int plane_normal_axis = 2;  ///< 0 x, 1 y, 2 z (the plane areas are counted on)
};

/// Connected regions of field.significant (per sign), grown by hysteresis when grow_k > 0, their
/// statistics and the area shares.
RegionAnalysis
analyseRegions(const std::vector<Eigen::Vector3d>& points, const ResidualField& field,
               const RegionSettings& settings);

}  // namespace deformation
}  // namespace pcl_ls3d
