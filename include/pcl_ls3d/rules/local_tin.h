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
planeNormal(const TargetSurface& target, const std::vector<int>& indices, int count, Eigen::Vector3d& normal);

/// Mean and covariance (divided by \a count) of the first \a count target points of \a indices.
Eigen::Matrix3d
neighbourhoodCovariance(const TargetSurface& target, const std::vector<int>& indices, int count,
                        Eigen::Vector3d& mean);

/// As planeNormal(), also giving the covariance eigenvalues (ascending: λ0 across the surface,
/// λ1 ≤ λ2 its spread in the tangent plane).
bool
neighbourhoodPca(const TargetSurface& target, const std::vector<int>& indices, int count,
                 Eigen::Vector3d& normal, Eigen::Vector3d& eigenvalues);

/// True when a neighbourhood spreads in both tangent directions (λ1 ≥ min_ratio·λ2). Anisotropic
/// scans (zig-zag lines converging at the swath edge) give k-NN sets that are one or two nearly
/// collinear lines: their PCA normal, and any surface fitted to them, is free to tilt about the
/// line, which biases the registration by decimetres.
bool
wellSpread(const Eigen::Vector3d& eigenvalues, double min_ratio = 0.1);

/// True when the query (the origin of `projected`) is surrounded by its neighbours, not at the
/// side of a one-sided set: the offset of their 2-D centroid from the query is at most
/// max_offset × their RMS distance from that centroid. At the border of the target (partial
/// overlap) the neighbours all lie inwards; a surface fitted there is extrapolated.
bool
centredSupport(const std::vector<Eigen::Vector2d>& projected, double max_offset);

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
/// False for fewer than 8 points or an ill-conditioned fit. `height_variance` (optional) gets
/// the variance factor q_aa = (AᵀA)⁻¹₀₀ of the height, i.e. σ²(a) / σ²(point): about 1/3 for
/// points well spread around the query, large when the neighbours lie on two scan lines (the
/// quadratic term along the line spacing is then undetermined and a is extrapolated).
/// `residual_variance` (optional) gets RSS / (count − 6), the points' noise about the quadric;
/// `slope_variance` (optional) the variances of the two slopes from that noise.
bool
quadricPatch(const TargetSurface& target, const std::vector<int>& indices, int count,
             const Eigen::Vector3d& query, const Eigen::Vector3d& normal, double& height,
             Eigen::Vector2d& slope, double* height_variance = nullptr, double* residual_variance = nullptr,
             Eigen::Vector2d* slope_variance = nullptr);

/// The orthonormal (e1, e2) used with `normal` by projectToPlane() and quadricPatch().
void
planeBasis(const Eigen::Vector3d& normal, Eigen::Vector3d& e1, Eigen::Vector3d& e2);

}  // namespace tin
}  // namespace pcl_ls3d
