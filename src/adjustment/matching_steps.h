#pragma once
// Internal steps of SurfaceMatchingCore::run (not installed): reduction origin, convergence and
// freeze tests, robust start scale, and the precision fields of the report.
#include <pcl_ls3d/adjustment/adjustment_report.h>
#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/adjustment/gauss_markov.h>
#include <pcl_ls3d/rules/target_surface.h>

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace detail {

/// Centroid of the source points whose image under the guess falls into the target's bounding
/// box (grown by a margin): the reduction origin o_s, near the overlap; also the target's box and
/// the indices of those source points. False: no overlap.
bool
overlapCentroid(const std::vector<Eigen::Vector3d>& source, const TargetSurface& target,
                const Eigen::Matrix4d& guess, double max_distance, Eigen::Vector3d& centroid,
                Eigen::AlignedBox3d& box, std::vector<int>& inside);

/// Zuo's criterion (every angle change below ε) plus translation and scale epsilons.
bool
converged(const Vector7d& dx, const AdjustmentSettings& s);

/// Every estimated parameter changed by less than `fraction` of its formal σ_i.
bool
changesBelow(const GaussMarkovSolution& sol, double fraction);

/// Robust stand-in for σ0 before the first solve: 1.4826 · median |l| of the first m values.
double
robustScale(const std::vector<double>& l, std::size_t m);

/// σ_i (√C_ii of report.covariance; 0 fixed, +inf undeterminable), formal σ0 √q_ii and the
/// correlation from C; returns the names of the undeterminable parameters.
std::string
fillPrecision(AdjustmentReport& report, const GaussMarkovSolution& sol);

}  // namespace detail
}  // namespace pcl_ls3d
