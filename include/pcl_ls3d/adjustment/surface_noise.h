#pragma once
/// \file surface_noise.h
/// \brief Robust estimates of a sampled surface's own noise σ (local quadric residuals), for the
///        errors-in-variables correction (the source) and the quality gate (σ0 against the noise
///        both surfaces carry). Roughness (vegetation, edges) counts as noise, so on rough ground
///        the figure is an upper bound.

#include <pcl_ls3d/rules/target_surface.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_ls3d {

/// \brief σ from local quadrics fitted to the points within `radius` of up to max_seeds seed
///        points (spread over `seeds`), pooled as the median of RSS/(k − 6) corrected to a mean.
///        Returns 0 when no seed has enough neighbours.
double
estimateSurfaceNoise(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& seeds, double radius,
                     std::size_t max_seeds = 256);

/// \brief The same on a TargetSurface: quadrics of the k nearest target points of up to
///        max_seeds positions (spread over `seeds`, e.g. the conjugate points of a match).
double
estimateSurfaceNoise(const TargetSurface& surface, const std::vector<Eigen::Vector3d>& seeds, int k = 30,
                     std::size_t max_seeds = 256);

/// \brief Median distance from a target point to its nearest other target point, over up to
///        `samples` points spread over the surface (0 for fewer than 2 points).
double
estimatePointSpacing(const TargetSurface& surface, std::size_t samples = 256);

}  // namespace pcl_ls3d
