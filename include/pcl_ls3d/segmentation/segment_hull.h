#pragma once
/// \file segment_hull.h
/// \brief Convex-hull contour points and volume of one segment (pcl::ConvexHull / qhull), with
///        the degenerate cases (tiny, collinear, flat) decided by PCA before qhull sees them.

#include <Eigen/Core>

#include <vector>

namespace pcl_ls3d {
namespace segmentation {

/// \brief Shape class of a point set, from the eigenvalues of its covariance.
enum class HullKind
{
  Empty,      ///< no points
  Tiny,       ///< fewer than 4 points, or all identical: contour = the points
  Collinear,  ///< λ2 ≤ tol·λ1: contour = the two extreme points along the line
  Flat,       ///< λ3 ≤ tol·λ1: 2-D hull in the best-fit plane, volume 0
  Solid       ///< 3-D hull and its volume
};

/// \brief Contour of a point set: indices into the input and the hull volume [m³].
struct SegmentHull
{
  HullKind kind = HullKind::Empty;
  std::vector<int> contour;  ///< indices into the points given to computeSegmentHull()
  double volume = 0.0;       ///< 0 unless kind == Solid
  /// Solid only: facet planes (n, d), outward unit n, n·x + d ≤ 0 inside.
  std::vector<Eigen::Vector4d> planes;
};

/// \brief True if every point lies inside the solid hull (within \a tol metres); false for
///        non-solid hulls. Adding such points leaves the hull, and its volume, unchanged.
bool
insideHull(const SegmentHull& hull, const std::vector<Eigen::Vector3f>& points, double tol);

/// \brief Relative eigenvalue tolerance below which a set counts as collinear / flat.
constexpr double kHullDegeneracyTolerance = 1e-9;

/// \brief Convex hull of \a points (coordinates in a local frame). Never fails: if qhull rejects
///        a nearly flat set, the 2-D hull is used; if that fails too, all points are the contour.
SegmentHull
computeSegmentHull(const std::vector<Eigen::Vector3f>& points);

}  // namespace segmentation
}  // namespace pcl_ls3d
