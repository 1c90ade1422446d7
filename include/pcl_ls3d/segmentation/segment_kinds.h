#pragma once
/// \file segment_kinds.h
/// \brief What kind of thing a segment is, from its geometry alone: the first step of the object
///        level of IMRG (object_assembly.h). PCL-free.
///
/// Kinds, tested in this order:
///  - Ground: most points pass the progressive morphological ground filter (ground_filter.h);
///  - Linear: elongated, √(λ2/λ1) < linear_ratio (wires, poles, roof edges);
///  - Rough: not flat (below) and the median plane-fit residual of its points
///    (PointFeatures::residual, the quantity of the paper's similarity condition) above
///    roughness_ratio times that of the ground points, i.e. clearly rougher than the scanner
///    noise: vegetation. On the IGN tiles and the generated scenes roof and car segments lie at
///    0.6–2 times the ground's residual and vegetation segments at 2.4–12 times
///    (docs/BENCHMARKS.md). A flat segment is a surface however rough its points: facades with
///    windows and recesses, gravel roofs (on the five IGN tiles 17 of 21 rough flat segments
///    were building, 2 of 1 052 rough vegetation segments were flat);
///  - Wall: flat, √(λ3/λ2) < flat_ratio, with a near-horizontal normal (|n_z| < wall_normal_z);
///  - Solid: the rest (roofs, car bodies).
/// λ1 ≥ λ2 ≥ λ3 are the eigenvalues of the segment's covariance.

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {

enum class SegmentKind : std::uint8_t
{
  Ground,
  Solid,
  Wall,
  Rough,
  Linear
};

/// \brief Thresholds of the kinds.
struct KindSettings
{
  double linear_ratio = 0.15;    ///< √(λ2/λ1) below: linear segment
  double flat_ratio = 0.15;      ///< √(λ3/λ2) below: flat segment
  double wall_normal_z = 0.35;   ///< |n_z| of a flat segment below: wall (about 70° from up)
  double roughness_ratio = 2.0;  ///< segment / ground median residual above: rough
};

/// \brief Moments and votes of one segment.
struct SegmentShape
{
  std::size_t n = 0;                                     ///< points
  std::size_t ground = 0;                                ///< points the ground filter keeps
  double median_residual = 0.0;                          ///< median PointFeatures::residual of its points
  Eigen::Vector3d lambda = Eigen::Vector3d::Zero();      ///< covariance eigenvalues, ascending
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();     ///< eigenvector of λ3
  Eigen::Vector3d principal = Eigen::Vector3d::UnitX();  ///< eigenvector of λ1
};

/// \brief Shape of every segment.
/// \param[in] points coordinates per point
/// \param[in] labels segment per point (dense 0..n−1, −1 none)
/// \param[in] residuals plane-fit residual per point (PointFeatures::residual)
/// \param[in] ground per point: 1 if the ground filter keeps it
std::vector<SegmentShape>
segmentShapes(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& labels,
              const std::vector<float>& residuals, const std::vector<char>& ground);

/// \brief Median residual of the ground points (all points when fewer than 10 are ground): the
///        noise level the roughness is measured in.
double
groundResidual(const std::vector<float>& residuals, const std::vector<char>& ground);

/// \brief Kind of one segment (rules in the file comment).
SegmentKind
kindOf(const SegmentShape& shape, double ground_residual, const KindSettings& settings);

/// \brief Are the segment's points rough (median residual above roughness_ratio times the
///        ground's), whatever its shape?
bool
hasRoughPoints(const SegmentShape& shape, double ground_residual, const KindSettings& settings);

}  // namespace segmentation
}  // namespace pcl_ls3d
