#pragma once
/// \file neighbour_noise.h
/// \brief The noise of a residual field from the differences of neighbouring residuals (von
///        Neumann 1941; Rice 1984), made robust with the MAD:
///          σ_d = 1.4826 · med_i |v_i − v_nn(i)| / √2,
///        nn(i) the nearest other point with a residual. A smooth part of the field — a fit
///        tilted towards a deformed patch, the patch itself, a slow drift — is nearly the same at
///        neighbours and cancels, so σ_d sees the point noise alone, where the MAD, LMS or LTS
///        scale of the residuals themselves also sees the smooth part. Gathered deformation
///        reaches σ_d only through its patch's rim and its own spread. PCL-free.

#include <Eigen/Core>

#include <vector>

namespace pcl_ls3d {

/// \param[in] points positions of the residuals (any frame; non-finite: skipped)
/// \param[in] residuals one per point (non-finite: the point has none)
/// \return σ_d, or 0 when fewer than two points have a residual. Points at the same position
///         are not neighbours (a duplicate would difference its own noise away).
double
neighbourDifferenceScale(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& residuals);

}  // namespace pcl_ls3d
