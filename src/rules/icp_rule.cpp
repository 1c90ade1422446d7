#include <pcl_ls3d/rules/icp_rule.h>
#include <pcl_ls3d/rules/local_tin.h>

#include <cmath>

namespace pcl_ls3d {

bool
IcpRule::findConjugate(const Eigen::Vector3d& query, const TargetSurface& target,
                       double max_distance, CorrespondenceCache& cache,
                       ConjugateObservations& out) const
{
  thread_local std::vector<int> indices;
  thread_local std::vector<float> sq_dists;
  thread_local std::vector<Eigen::Vector2d> projected;
  const int k = require_enclosure_ ? neighbours_ : 1;
  const int found = target.nearestKSearch(query, k, indices, sq_dists);
  if (found < 1 || !(static_cast<double>(sq_dists[0]) <= max_distance * max_distance))
    return false;
  if (require_enclosure_) {
    // Overlap test: the query must lie inside the local surface, not beyond its border.
    Eigen::Vector3d normal;
    std::array<int, 3> tri;
    if (!tin::planeNormal(target, indices, found, normal))
      return false;
    tin::projectToPlane(target, indices, found, query, normal, projected);
    if (!tin::enclosingTriangle(projected, tri))
      return false;
  }
  const Eigen::Vector3d q = target.point(indices[0]);
  cache.vertices[0] = indices[0];
  for (int axis = 0; axis < 3; ++axis)
    out.add(Eigen::Vector3d::Unit(axis), query[axis] - q[axis], q);
  return true;
}

}  // namespace pcl_ls3d
