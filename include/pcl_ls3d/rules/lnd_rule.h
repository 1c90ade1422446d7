#pragma once
/// \file lnd_rule.h
/// \brief LND rule (least normal distance; Zuo et al. 2012, Fig. 1a): the conjugate point is the
///        foot of the transformed source point on the local TIN triangle of the target; the
///        observation is the signed distance along that triangle's normal.

#include <pcl_ls3d/rules/conjugate_rule.h>

namespace pcl_ls3d {

/// \brief Local TIN triangle: from the k nearest target points, the most compact triangle that
///        encloses the query in the neighbourhood's tangent plane. No enclosing triangle = the
///        query lies outside the target surface = no correspondence (overlap handling).
///        The triangle is cached per source point and reused while the point still projects
///        into it, so later iterations need no neighbour search.
class LndRule final : public ConjugateRule
{
public:
  explicit LndRule(int neighbours = 8) : neighbours_(neighbours) {}
  std::string
  name() const override
  {
    return "LND";
  }
  bool
  findConjugate(const Eigen::Vector3d& query, const TargetSurface& target, double max_distance,
                CorrespondenceCache& cache, ConjugateObservations& out) const override;

private:
  const int neighbours_;
};

}  // namespace pcl_ls3d
