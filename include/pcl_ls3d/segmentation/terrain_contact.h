#pragma once
/// \file terrain_contact.h
/// \brief What lies on the terrain is ground: points of vegetation objects (and of cars, which
///        IMRG grows as rough objects too) that the ground filter keeps and that lie within the
///        terrain's own noise of it join the ground object beside them. PCL-free.
///
/// The growth puts the ground at a crown's or a hedge's foot into the rough segment standing
/// on it (rough with rough: the ground's points take the crown's noisy neighbourhoods). The
/// mirror of the assembly's raised points (object_assembly.h, raised_noise_multiple): there,
/// filter-kept points of ground segments higher than a few ground residuals above the
/// terrain plane around them leave the ground (grass); here, filter-kept points of vegetation
/// objects no higher than \a limit above that plane (heightAboveTerrain, ground_filter.h) join
/// the ground object with which they share the most k-NN links (of any length: the point lies
/// on the terrain already, the links only say which ground object). Rounds repeat until
/// nothing moves, each deciding on the labels as the round found them, so the ground under a
/// bush's rim returns from the lawn inwards; a point stays unless a chain of such points links
/// it to a ground object.

#include <pcl_ls3d/segmentation/object_classes.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {

/// \brief Moves the vegetation and car points lying on the terrain into the ground (rule above).
/// \param[in] points coordinates per point (non-finite ones are left alone)
/// \param[in] ground per point: 1 if the ground filter keeps it
/// \param[in] graph k-NN graph, \a graph_k neighbour positions per point (−1: none)
/// \param[in] object_class per object (index = label), classifyObjects()
/// \param[in] limit height above the terrain plane up to which a point lies on it [m]
/// \param[in] half_width half width of the terrain window (heightAboveTerrain) [m]
/// \param[in,out] labels object per point (−1 none)
/// \return the number of points moved; 0 when the sizes differ, graph_k ≤ 0 or limit is not
///         positive
std::size_t
returnTerrainPoints(const std::vector<Eigen::Vector3f>& points, const std::vector<char>& ground,
                    const std::vector<int>& graph, int graph_k, const std::vector<ObjectClass>& object_class,
                    double limit, double half_width, std::vector<int>& labels);

}  // namespace segmentation
}  // namespace pcl_ls3d
