#pragma once
// Checks of a pair (not installed): does the source, under the guess, lie over the target (before
// any conjugate point is sought), and, when no rule found one, is the target degenerate there?
// Shared by the LS3D pair engine (adjustment/) and LinearizedMatching (sample_consensus/), so both
// paths name a failure alike.
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

/// Why no rule found a conjugate point although source points lie over the target: "collinear"
/// or "coincident" when the target's points nearest to every sampled source point (under the
/// guess) are so, and no local surface can be fitted there; "" when they span a surface.
std::string
degenerateTarget(const std::vector<Eigen::Vector3d>& source, const std::vector<int>& inside,
                 const Eigen::Matrix4d& guess, const TargetSurface& target);

/// The failure line for a degenerate target, in the caller's names for the two clouds ("target"
/// and "source", "reference" and "epoch"): "no observation: the <target> has no surface the
/// rule can fit where the <source> lies over it (degenerate: its points there are collinear)";
/// "" when degenerateTarget() finds a surface.
std::string
degenerateTargetReason(const std::vector<Eigen::Vector3d>& source, const std::vector<int>& inside,
                       const Eigen::Matrix4d& guess, const TargetSurface& target,
                       const std::string& target_name, const std::string& source_name);

}  // namespace detail
}  // namespace pcl_ls3d
