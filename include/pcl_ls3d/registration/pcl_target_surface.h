#pragma once
/// \file pcl_target_surface.h
/// \brief Adapter: a PCL target cloud and its search object seen as a TargetSurface, so the
///        PCL-free rules and core can query the kd-tree pcl::Registration already built.

#include <pcl_ls3d/rules/target_surface.h>

#include <pcl/point_cloud.h>
#include <pcl/search/search.h>

#include <type_traits>

namespace pcl_ls3d {

/// \brief Wraps (cloud, search) without copying either. The search must already be built on
///        the cloud (pcl::Registration::initCompute does that).
template <typename PointT>
class PclTargetSurface : public TargetSurface
{
public:
  using Cloud = pcl::PointCloud<PointT>;
  using Search = pcl::search::Search<PointT>;

  PclTargetSurface(const typename Cloud::ConstPtr& cloud, const typename Search::Ptr& search)
      : cloud_(cloud), search_(search)
  {}

  std::size_t
  size() const override
  {
    return cloud_->size();
  }

  Eigen::Vector3d
  point(int index) const override
  {
    return (*cloud_)[static_cast<std::size_t>(index)].getVector3fMap().template cast<double>();
  }

  int
  nearestKSearch(const Eigen::Vector3d& query, int k, std::vector<int>& indices,
                 std::vector<float>& sq_dists) const override
  {
    static_assert(std::is_same<pcl::Indices, std::vector<int>>::value,
                  "pcl::Indices must be std::vector<int>");
    PointT p;
    p.x = static_cast<float>(query.x());
    p.y = static_cast<float>(query.y());
    p.z = static_cast<float>(query.z());
    return search_->nearestKSearch(p, k, indices, sq_dists);
  }

private:
  typename Cloud::ConstPtr cloud_;
  typename Search::Ptr search_;
};

}  // namespace pcl_ls3d
