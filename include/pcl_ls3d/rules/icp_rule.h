#pragma once
/// \file icp_rule.h
/// \brief ICP rule (Besl & McKay 1992; Zuo et al. 2012, Fig. 1c): the conjugate point is the
///        closest target point; three observations, the components of x' − q along the three
///        axes of the closest point's error ellipsoid (local normal and two tangents).
///
/// Weighting: q stands in for the true conjugate point with an anisotropic error: the target
/// noise σ_n across the surface, an offset anywhere within the k-neighbourhood along it (r_k²/4
/// per axis). Equal weights on the three axes (the plain point-to-point form) let the tangential
/// components, which carry only that sampling offset (re-drawn at every re-association, and
/// biased inwards at the target's border), anchor the estimate and pull it towards the border.
/// Weighting each axis by 1/variance (tangents p_t = σ_n²/(σ_n² + r_k²/4), normal 1) is the
/// least-squares form of the same three observations; with the engine's Besl & McKay
/// acceleration it converges (figures in docs/ARCHITECTURE.md).
/// When the engine freezes correspondences the rule keeps its closest point and axes.

#include <pcl_ls3d/rules/conjugate_rule.h>

namespace pcl_ls3d {

/// \brief Closest target point. The k nearest target points give the local normal and density;
///        with require_enclosure (default), a query is used only when a triangle of them
///        encloses it in the local tangent plane, so points beyond the target's border (partial
///        overlap) do not pull towards the border.
class IcpRule final : public ConjugateRule
{
public:
  explicit IcpRule(bool require_enclosure = true, int neighbours = 8)
      : require_enclosure_(require_enclosure), neighbours_(neighbours)
  {}
  std::string
  name() const override
  {
    return "ICP";
  }
  int
  maxObservations() const override
  {
    return 3;
  }
  bool
  findConjugate(const Eigen::Vector3d& query, const TargetSurface& target, double max_distance,
                CorrespondenceCache& cache, ConjugateObservations& out) const override;

private:
  const bool require_enclosure_;
  const int neighbours_;
};

}  // namespace pcl_ls3d
