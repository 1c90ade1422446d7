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
  enum class Surface {
    TRIANGLE,     ///< the enclosing TIN triangle itself (Zuo et al.; Gruen & Akca)
    LOCAL_PLANE,  ///< the least-squares plane of the k neighbours (normal less noisy: see below)
    LOCAL_QUADRIC ///< a least-squares quadric of the k neighbours: no curvature bias (default)
  };
  /// LOCAL_QUADRIC is the default: on noisy data a triangle normal's own noise enters the design
  /// matrix (errors in variables) and shrinks every step, so the estimate creeps towards the
  /// truth and stops short of it; a k-point fit is much less noisy. A plane (or a facet) lies
  /// inside curved terrain, which flattens the relief and biases the scale m; the quadric does
  /// not. The enclosing-triangle test still decides whether the point lies over the target.
  /// 20 neighbours: the fitted surface's own noise enters the slopes (errors in variables) and
  /// attenuates the horizontal parameters; with 12 the 300 m benchmark pair ended 9.2 mm off,
  /// with 20 4.3 mm (24: 5.0 mm; wider sets start to smooth the relief).
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
