#pragma once
/// \file point_to_point_rule.h
/// \brief Plain point-to-point observations (Besl & McKay 1992): the closest target point q and
///        the three components of x' − q along the axes, equal weights. What
///        LeastSquaresSurfaceMatching falls back to for clouds too small for a local surface
///        (PCL's five-point ICP_translated test): IcpRule weights its tangents by a local plane
///        fit, which a handful of scattered points cannot give.

#include <pcl_ls3d/rules/conjugate_rule.h>

#include <vector>

namespace pcl_ls3d {

class PointToPointRule final : public ConjugateRule
{
public:
  std::string
  name() const override
  {
    return "point-to-point";
  }
  int
  maxObservations() const override
  {
    return 3;
  }
  bool
  findConjugate(const Eigen::Vector3d& query, const TargetSurface& target, double max_distance,
                CorrespondenceCache& cache, ConjugateObservations& out) const override
  {
    int idx = cache.vertices[0];
    if (!cache.frozen) {  // frozen: keep the closest point found last
      thread_local std::vector<int> indices;
      thread_local std::vector<float> sq_dists;
      idx = target.nearestKSearch(query, 1, indices, sq_dists) >= 1 ? indices[0] : -1;
      cache.vertices[0] = idx;
    }
    if (idx < 0 || idx >= static_cast<int>(target.size()))
      return false;
    const Eigen::Vector3d q = target.point(idx);
    const Eigen::Vector3d d = query - q;
    if (!(d.norm() <= max_distance))
      return false;
    for (int axis = 0; axis < 3; ++axis)
      out.add(Eigen::Vector3d::Unit(axis), d[axis], q);
    return true;
  }
};

}  // namespace pcl_ls3d
