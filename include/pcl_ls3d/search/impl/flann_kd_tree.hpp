#pragma once

#include <pcl_ls3d/search/flann_kd_tree.h>

#include <pcl/common/point_tests.h>
#include <pcl/console/print.h>
#include <pcl/point_representation.h>

#include <flann/util/result_set.h>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {
namespace search {

template <typename PointT>
bool
FlannKdTree<PointT>::searchesCoordinates() const
{
  const auto representation = this->getPointRepresentation();
  return representation && representation->getNumberOfDimensions() == 3 &&
         dynamic_cast<const pcl::DefaultPointRepresentation<PointT>*>(representation.get());
}

template <typename PointT>
void
FlannKdTree<PointT>::setInputCloud(const PointCloudConstPtr& cloud, const pcl::IndicesConstPtr& indices)
{
  index_.reset();
  coordinates_.clear();
  tree_to_input_.clear();
  direct_ = searchesCoordinates();
  if (!direct_) {
    Base::setInputCloud(cloud, indices);
    return;
  }
  this->input_ = cloud;
  this->indices_ = indices;
  if (!cloud)
    return;

  const std::size_t candidates = indices ? indices->size() : cloud->size();
  coordinates_.reserve(3 * candidates);
  tree_to_input_.reserve(candidates);
  for (std::size_t i = 0; i < candidates; ++i) {
    const pcl::index_t input_index = indices ? (*indices)[i] : static_cast<pcl::index_t>(i);
    const PointT& p = (*cloud)[static_cast<std::size_t>(input_index)];
    if (!pcl::isXYZFinite(p))
      continue;
    coordinates_.insert(coordinates_.end(), {p.x, p.y, p.z});
    tree_to_input_.push_back(input_index);
  }
  if (tree_to_input_.empty()) {
    PCL_DEBUG("[pcl_ls3d::search::FlannKdTree::setInputCloud] no finite point to index\n");
    return;
  }
  const flann::Matrix<float> points(coordinates_.data(), tree_to_input_.size(), 3);
  index_ = std::make_unique<Index>(points, flann::KDTreeSingleIndexParams(15));
  index_->buildIndex();
}

template <typename PointT>
int
FlannKdTree<PointT>::nearestKSearch(const PointT& point, int k, pcl::Indices& k_indices,
                                    std::vector<float>& k_sqr_distances) const
{
  if (!direct_)
    return Base::nearestKSearch(point, k, k_indices, k_sqr_distances);
  k_indices.clear();
  k_sqr_distances.clear();
  if (!index_ || k <= 0 || !pcl::isXYZFinite(point))
    return 0;

  const std::size_t wanted = std::min<std::size_t>(static_cast<std::size_t>(k), tree_to_input_.size());
  flann::KNNSimpleResultSet<float> result(wanted);
  const float query[3] = {point.x, point.y, point.z};
  index_->findNeighbors(result, query, flann::SearchParams(-1, this->getEpsilon()));

  std::vector<std::size_t> found(wanted);
  k_sqr_distances.resize(wanted);
  result.copy(found.data(), k_sqr_distances.data(), wanted);
  k_indices.resize(wanted);
  for (std::size_t i = 0; i < wanted; ++i)
    k_indices[i] = inputIndex(found[i]);
  return static_cast<int>(wanted);
}

template <typename PointT>
int
FlannKdTree<PointT>::radiusSearch(const PointT& point, double radius, pcl::Indices& k_indices,
                                  std::vector<float>& k_sqr_distances, unsigned int max_nn) const
{
  if (!direct_)
    return Base::radiusSearch(point, radius, k_indices, k_sqr_distances, max_nn);
  k_indices.clear();
  k_sqr_distances.clear();
  if (!index_ || !(radius >= 0.0) || !pcl::isXYZFinite(point))
    return 0;

  const float query[3] = {point.x, point.y, point.z};
  const flann::SearchParams params(-1, this->getEpsilon(), this->sorted_results_);
  const float sq_radius = static_cast<float>(radius * radius);
  std::vector<std::size_t> found;
  const auto collect = [&](auto& result) {
    index_->findNeighbors(result, query, params);
    found.resize(result.size());
    k_sqr_distances.resize(result.size());
    result.copy(found.data(), k_sqr_distances.data(), result.size(), this->sorted_results_);
  };
  if (max_nn == 0 || max_nn >= tree_to_input_.size()) {
    flann::RadiusResultSet<float> result(sq_radius);
    collect(result);
  } else {
    flann::KNNRadiusResultSet<float> result(sq_radius, max_nn);
    collect(result);
  }
  k_indices.resize(found.size());
  for (std::size_t i = 0; i < found.size(); ++i)
    k_indices[i] = inputIndex(found[i]);
  return static_cast<int>(found.size());
}

}  // namespace search
}  // namespace pcl_ls3d

#define PCL_LS3D_INSTANTIATE_FlannKdTree(T) template class PCL_EXPORTS pcl_ls3d::search::FlannKdTree<T>;
