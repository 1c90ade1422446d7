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
  /// Which surface element gives the height and its slope.
  enum class Surface
  {
    TRIANGLE,      ///< the XY-enclosing TIN triangle itself (Rosenholm; Zuo et al.)
    LOCAL_PLANE,   ///< the least-squares plane of the k neighbours (see LndRule)
    LOCAL_QUADRIC  ///< a least-squares quadric z(x, y) of the k neighbours (default; see LndRule)
  };
  explicit LzdRule(int neighbours = 20, Surface surface = Surface::LOCAL_QUADRIC)
      : neighbours_(neighbours), surface_(surface)
  {}
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
  const Surface surface_;
};

}  // namespace pcl_ls3d
