#pragma once
/// \file observation_set.h
/// \brief What stage 2 (the pair matcher) hands to the adjustment: one record per observation
///        with its identity (which source point, which of the rule's observations), where it
///        is, and what was measured. Estimators, the precision stage and the block adjustment
///        all read this set; none keeps private copies of it.

#include <Eigen/Core>

#include <cstddef>
#include <limits>
#include <vector>

namespace pcl_ls3d {

/// \brief One conjugate-point observation l = uᵀ(T_s(p) − T_t(q)) (Zuo et al. 2012, §2.2).
struct Observation
{
  /// Index of the observed source point in the matcher's point list: the same point keeps the
  /// same index in every iteration, so an estimator can follow it.
  int point = -1;
  /// Which of the rule's observations of that point (0 for LND/LZD; 0..2 for ICP's axes).
  int component = 0;
  /// u = ∂l/∂x_out in the common frame (unit for distance rules; LZD: (−∂z/∂x, −∂z/∂y, 1)).
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  /// Signed l at the current parameters (common-frame units).
  double distance = 0.0;
  /// Conjugate point q on the target surface, in the target's own (input) coordinates.
  Eigen::Vector3d foot = Eigen::Vector3d::Zero();
  /// Variance of the local target surface at q along u; NaN when the rule does not estimate it.
  double surface_variance = std::numeric_limits<double>::quiet_NaN();
};

/// \brief The observations of one iteration, ordered by source point (then component).
class ObservationSet
{
public:
  std::size_t
  size() const
  {
    return items_.size();
  }
  bool
  empty() const
  {
    return items_.empty();
  }
  const Observation&
  operator[](std::size_t j) const
  {
    return items_[j];
  }
  Observation&
  operator[](std::size_t j)
  {
    return items_[j];
  }
  std::vector<Observation>::const_iterator
  begin() const
  {
    return items_.begin();
  }
  std::vector<Observation>::const_iterator
  end() const
  {
    return items_.end();
  }

  /// The signed distances l as one vector (what weight functions look at).
  Eigen::VectorXd
  distances() const
  {
    Eigen::VectorXd l(static_cast<Eigen::Index>(items_.size()));
    for (std::size_t j = 0; j < items_.size(); ++j)
      l[static_cast<Eigen::Index>(j)] = items_[j].distance;
    return l;
  }

  /// Storage, for the matcher that fills it.
  std::vector<Observation>&
  items()
  {
    return items_;
  }

private:
  std::vector<Observation> items_;
};

}  // namespace pcl_ls3d
