#pragma once
/// \file icp_rule.h
/// \brief ICP rule (Besl & McKay 1992; Zuo et al. 2012, Fig. 1c): the conjugate point is the
///        closest target point; three observations, the coordinate differences along x, y, z.

#include <pcl_ls3d/rules/conjugate_rule.h>

namespace pcl_ls3d {

/// \brief Closest target point. With require_enclosure (default), a query is used only when a
///        triangle of its k nearest target points encloses it in the local tangent plane, so
///        points beyond the target's border (partial overlap) do not pull towards the border.
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
