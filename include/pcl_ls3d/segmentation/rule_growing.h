#pragma once
/// \file rule_growing.h
/// \brief The growing stage of (I)MRG: one region-growing rule per dimensionality set over a
///        k-NN graph (Wang et al. 2021 §2 and §3.1). PCL-free.

#include <pcl_ls3d/segmentation/dimensionality_features.h>

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {

/// \brief Settings of growRegions(). Angles in radians, lengths in metres.
struct GrowingSettings
{
  int graph_k = 16;                              ///< neighbours per point in the growth graph
  double principal_angle = 15.0 * M_PI / 180.0;  ///< M_t, linear rule
  double normal_angle = 10.0 * M_PI / 180.0;     ///< N_t, planar rule
  double growth_radius = 0.0;                    ///< max neighbour distance, linear and planar rules
  double volumetric_radius = 0.0;                ///< connectivity radius, volumetric rule
  bool use_seed_condition = true;                ///< IMRG §3.1
  double residual_threshold = std::numeric_limits<double>::quiet_NaN();  ///< v_t [m]
};

/// \brief Grow segments inside each dimensionality set.
///
/// A neighbour j of i (both in the same set, j in i's graph row) joins i's segment when
///  - linear:     |d_i · d_j| ≥ cos M_t and ‖p_i − p_j‖ ≤ growth_radius;
///  - planar:     |n_i · n_j| ≥ cos N_t and ‖p_i − p_j‖ ≤ growth_radius, and (an addition to
///                the paper) p_j on i's tangent plane: |n_i · (p_j − p_i)| ≤ growth_radius ·
///                sin N_t, the offset a plane tilted by N_t reaches over one step. Without it
///                a parallel surface beside a roof edge (the top of a crown or hedge, a step
///                of a few decimetres) grows into the roof;
///  - volumetric: ‖p_i − p_j‖ ≤ volumetric_radius.
/// Seeds are taken in order of increasing residual (as pcl::RegionGrowing orders by curvature).
/// With the seed condition, a planar point other than the seed propagates only if its residual
/// is < residual_threshold: boundary points are absorbed but do not carry growth across an edge.
/// \param[in] points coordinates per position
/// \param[in] features per position; Invalid points are never labelled
/// \param[in] normals per position, used by the planar rule (usually features[i].normal)
/// \param[in] graph row-major, graph_k positions per position, −1 padded
/// \return segment id per position (dense from 0), −1 for Invalid points
std::vector<int>
growRegions(const std::vector<Eigen::Vector3f>& points, const std::vector<PointFeatures>& features,
            const std::vector<Eigen::Vector3f>& normals, const std::vector<int>& graph,
            const GrowingSettings& settings);

}  // namespace segmentation
}  // namespace pcl_ls3d
