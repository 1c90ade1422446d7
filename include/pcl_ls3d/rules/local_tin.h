#pragma once
/// \file local_tin.h
/// \brief Small geometric helpers shared by the TIN-based rules (and available to custom
///        rules): the local tangent plane of a neighbourhood and the triangle of neighbours
///        that encloses a query point in a 2-D projection (Zuo et al. 2012, Fig. 1/3).

#include <pcl_ls3d/rules/target_surface.h>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace pcl_ls3d {
namespace tin {

/// Unit normal of the least-squares plane through the given target points (PCA, smallest
/// eigenvector). False for fewer than 3 points or a degenerate (collinear) set.
bool
planeNormal(const TargetSurface& target, const std::vector<int>& indices, int count,
            Eigen::Vector3d& normal);

/// True when the origin lies inside (or on the border of) the 2-D triangle a, b, c.
bool
containsOrigin(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

/// Among 2-D points given relative to the query (query = origin), ordered nearest first, the
/// most compact triangle enclosing the origin (smallest sum of vertex distances); triangles
/// through the nearest point are tried first. Returns false when none encloses the query
/// (the query is outside the local surface: no overlap there).
bool
enclosingTriangle(const std::vector<Eigen::Vector2d>& points, std::array<int, 3>& triangle);

/// Projects 3-D target points (given by index) into the plane with unit normal `normal`, in 2-D
/// coordinates relative to `query`.
void
projectToPlane(const TargetSurface& target, const std::vector<int>& indices, int count,
               const Eigen::Vector3d& query, const Eigen::Vector3d& normal,
               std::vector<Eigen::Vector2d>& projected);

/// Fits w = a + b u + c v + d u² + e uv + f v² to the points in the frame (e1, e2, normal)
/// centred on `query` (w along `normal`), i.e. a local quadric surface without the curvature
/// bias of a plane or a TIN facet. Returns the height a at the query and the slope (b, c).
/// False for fewer than 8 points or an ill-conditioned fit.
bool
quadricPatch(const TargetSurface& target, const std::vector<int>& indices, int count,
             const Eigen::Vector3d& query, const Eigen::Vector3d& normal, double& height,
             Eigen::Vector2d& slope);

/// The orthonormal (e1, e2) used with `normal` by projectToPlane() and quadricPatch().
void
planeBasis(const Eigen::Vector3d& normal, Eigen::Vector3d& e1, Eigen::Vector3d& e2);

}  // namespace tin
}  // namespace pcl_ls3d
