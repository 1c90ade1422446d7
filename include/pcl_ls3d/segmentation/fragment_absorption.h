#pragma once
/// \file fragment_absorption.h
/// \brief Absorption of tiny segments after IMRG merging. Region growing with strict rules
///        leaves many fragments of a few points (edges, leaves, clutter) that the hull-based
///        merging of §3.2 does not join because their nearest segment fails s_t or V_t. This is
///        an addition to Wang et al. 2021, off when the minimum size is 0. PCL-free.

#include <cstddef>
#include <functional>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {

/// \brief Rule: segments are visited from the smallest; a segment still under \a min_size
///        points joins the adjacent segment with which it shares the most k-NN graph links
///        (edges from its points to points of the other segment; ties: the larger segment,
///        then the smaller id). Sizes grow as fragments join, so a cluster of fragments (a
///        tree crown cut into leaves) first joins itself and then stops once it reaches
///        \a min_size. A fragment with no link to another segment stays as it is. Unlabelled
///        points (label < 0) are never targets.
/// \param[in] graph k-NN graph, \a graph_k positions per point (−1 = no neighbour)
/// \param[in] graph_k neighbours per point in \a graph
/// \param[in,out] labels segment id per point (dense 0..n−1, −1 none); relabelled densely
/// \param[in] min_size segments under this many points are absorbed (0 or 1: nothing happens)
/// \param[in] linkable optional: only links p → q for which it returns true count (the plane
///            level passes the planar growth rule, so a wall fragment never joins the roof it
///            touches at the eave); empty: every link counts
/// \return number of segments absorbed
std::size_t
absorbFragments(const std::vector<int>& graph, int graph_k, std::vector<int>& labels, std::size_t min_size,
                const std::function<bool(int, int)>& linkable = {});

}  // namespace segmentation
}  // namespace pcl_ls3d
