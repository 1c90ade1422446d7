#pragma once
/// \file similarity_jacobian.h
/// \brief The rigorous linearisation of x' = t + m R(φ, ω, κ) x (Zuo et al. 2012, eq. 2) at the
///        current estimate: the 3×7 Jacobian ∂x'/∂X and the design-matrix row a = uᵀ ∂x'/∂X.
///        Built once per iteration (rotation derivatives), then evaluated per point.

#include <pcl_ls3d/common/similarity_transform.h>

namespace pcl_ls3d {

using Matrix37d = Eigen::Matrix<double, 3, 7>;
using RowVector7d = Eigen::Matrix<double, 1, 7>;

/// \brief x' = t + m R x and its derivatives at fixed parameters X = (t, φ, ω, κ, m).
class SimilarityLinearization
{
public:
  explicit SimilarityLinearization(const SimilarityTransform& X);

  /// x' = t + m R x.
  Eigen::Vector3d
  apply(const Eigen::Vector3d& x) const
  {
    return t_ + mR_ * x;
  }

  /// ∂x'/∂X = [ I | m ∂R/∂φ x | m ∂R/∂ω x | m ∂R/∂κ x | R x ].
  Matrix37d
  jacobian(const Eigen::Vector3d& x) const;

  /// Design-matrix row a = uᵀ ∂x'/∂X for an observation along unit direction u.
  RowVector7d
  designRow(const Eigen::Vector3d& u, const Eigen::Vector3d& x) const;

private:
  Eigen::Vector3d t_;
  Eigen::Matrix3d R_, mR_, mdR_phi_, mdR_omega_, mdR_kappa_;
};

/// \brief Column scaling of the rank test for the 7 parameters of a body whose reduced points
///        reach \a radius from its origin: a unit change of each scaled parameter (translation,
///        angle × radius, scale × radius) displaces the edge of the data by about one unit.
///        1 for a radius ≤ 0.
Vector7d
rankTestScaling(double radius);

}  // namespace pcl_ls3d
