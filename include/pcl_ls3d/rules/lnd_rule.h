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
  /// Which surface element gives the normal and the foot point.
  enum class Surface
  {
    TRIANGLE,      ///< the enclosing TIN triangle itself (Zuo et al.; Gruen & Akca)
    LOCAL_PLANE,   ///< the least-squares plane of the k neighbours (normal less noisy: see below)
    LOCAL_QUADRIC  ///< a least-squares quadric of the k neighbours: no curvature bias (default)
  };
  /// LOCAL_QUADRIC is the default: a triangle normal's own noise enters the design matrix (errors
  /// in variables) and the estimate stops short of the truth; a plane or a facet inside curved
  /// terrain biases the scale; a k-point quadric does neither. The enclosing-triangle test still
  /// decides whether the point lies over the target. 20 neighbours: fewer let the fitted
  /// surface's noise attenuate the horizontal parameters, more smooth the relief
  /// (docs/ARCHITECTURE.md, "Where the defaults come from").
  explicit LndRule(int neighbours = 20, Surface surface = Surface::LOCAL_QUADRIC)
      : neighbours_(neighbours), surface_(surface)
  {}
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
  const Surface surface_;
};

}  // namespace pcl_ls3d
