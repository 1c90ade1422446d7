#pragma once
/// \file lzd_rule.h
/// \brief LZD rule (least z-difference, Rosenholm 1988; Zuo et al. 2012, Fig. 1b): the
///        conjugate point is the vertical intersection with the target triangle that contains
///        the query in XY; the observation is the height difference along z, linearised
///        rigorously (gradient (−∂z/∂x, −∂z/∂y, 1) of the triangle), so tx, ty are observable
///        on sloped terrain.

#include <pcl_ls3d/rules/conjugate_rule.h>

namespace pcl_ls3d {

/// \brief Vertical intersection with the XY-enclosing triangle of the k nearest target points.
///        No enclosing triangle (outside the target in plan) = no correspondence. Cached per
///        source point like LndRule.
class LzdRule final : public ConjugateRule
{
public:
  explicit LzdRule(int neighbours = 8) : neighbours_(neighbours) {}
  std::string
  name() const override
  {
    return "LZD";
  }
  bool
  findConjugate(const Eigen::Vector3d& query, const TargetSurface& target, double max_distance,
                CorrespondenceCache& cache, ConjugateObservations& out) const override;

private:
  const int neighbours_;
};

}  // namespace pcl_ls3d
