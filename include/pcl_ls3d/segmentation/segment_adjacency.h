#pragma once
/// \file segment_adjacency.h
/// \brief Which segments touch, and how much: the number of k-NN graph links between the points
///        of two segments. PCL-free.

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {

/// \brief One pair of touching segments (a < b) and the links between them (edges p → q of the
///        k-NN graph with p in one segment and q in the other, counted in both directions).
struct SegmentLink
{
  int a = 0, b = 0;
  std::size_t links = 0;
};

/// \brief All touching pairs, sorted by (a, b).
/// \param[in] points coordinates per point
/// \param[in] graph k-NN graph, \a graph_k positions per point, −1 padded
/// \param[in] labels segment per point (−1: none, never linked)
/// \param[in] max_length links longer than this do not count (k-NN edges reach across gaps
///            in sparse areas; two segments a gap apart do not touch)
std::vector<SegmentLink>
segmentAdjacency(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& graph, int graph_k,
                 const std::vector<int>& labels, double max_length);

}  // namespace segmentation
}  // namespace pcl_ls3d
