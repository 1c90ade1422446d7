#pragma once
/// \file flann_kd_tree.h
/// \brief A pcl::search::KdTree that queries FLANN's single kd-tree directly.

#include <pcl/point_cloud.h>
#include <pcl/search/kdtree.h>

#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>

#include <memory>
#include <vector>

namespace pcl_ls3d {
namespace search {

/// \brief Drop-in for pcl::search::KdTree<PointT> (the same tree, the same answers) without its
///        per-query cost. PCL's KdTreeFLANN sends every single query through FLANN's batch
///        knnSearch, which opens an OpenMP parallel region and allocates for one point; LS3D asks
///        a million such queries per iteration from its own parallel loops, where that overhead
///        was a quarter of the run time. This class builds the same FLANN KDTreeSingleIndex
///        (leaves of 15 points, as PCL) and calls findNeighbors() on it.
///
/// It is what pcl_ls3d::LeastSquaresSurfaceMatching uses by default for its target, and it can
/// be passed wherever a pcl::search::KdTree<PointT>::Ptr is expected. Points with a non-finite
/// coordinate are left out and indices refer to the input cloud, exactly as PCL's. With a
/// point representation other than PCL's default x, y, z one, it behaves as its base class.
template <typename PointT>
class FlannKdTree : public pcl::search::KdTree<PointT>
{
public:
  using Base = pcl::search::KdTree<PointT>;
  using Ptr = std::shared_ptr<FlannKdTree<PointT>>;
  using ConstPtr = std::shared_ptr<const FlannKdTree<PointT>>;
  using PointCloudConstPtr = typename Base::PointCloudConstPtr;
  using Base::nearestKSearch;
  using Base::radiusSearch;

  explicit FlannKdTree(bool sorted = true) : Base(sorted)
  {
    this->name_ = "FlannKdTree";
  }

  void
  setInputCloud(const PointCloudConstPtr& cloud,
                const pcl::IndicesConstPtr& indices = pcl::IndicesConstPtr()) override;

  int
  nearestKSearch(const PointT& point, int k, pcl::Indices& k_indices,
                 std::vector<float>& k_sqr_distances) const override;

  int
  radiusSearch(const PointT& point, double radius, pcl::Indices& k_indices,
               std::vector<float>& k_sqr_distances, unsigned int max_nn = 0) const override;

private:
  using Index = flann::KDTreeSingleIndex<flann::L2_Simple<float>>;

  /// True when the tree searches x, y, z only (PCL's default representation of PointT).
  bool
  searchesCoordinates() const;

  /// Input-cloud index of the i-th point the tree holds.
  pcl::index_t
  inputIndex(std::size_t tree_index) const
  {
    return tree_to_input_[tree_index];
  }

  bool direct_ = false;                      ///< false: everything goes to the base class
  std::vector<float> coordinates_;           ///< x, y, z of the finite points, row by row
  std::vector<pcl::index_t> tree_to_input_;  ///< tree point -> input-cloud index
  std::unique_ptr<Index> index_;
};

}  // namespace search
}  // namespace pcl_ls3d

#ifdef PCL_NO_PRECOMPILE
#include <pcl_ls3d/search/impl/flann_kd_tree.hpp>
#endif
