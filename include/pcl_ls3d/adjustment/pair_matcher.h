#pragma once
/// \file pair_matcher.h
/// \brief Stage 2 of the engine: the conjugate points of one source cloud on one target surface
///        (Zuo et al. 2012, §2.2) for given poses of both bodies, and the design rows of both
///        parameter blocks. A pair adjustment calls it with the target fixed at the identity; a
///        strip block adjustment calls one matcher per overlap with both strips moving.
///
/// Each source point p, mapped into the common frame by the source block (x = T_s(p)) and
/// from there into the target's own coordinates (y = T_t⁻¹(x)), is handed to the rule, which
/// returns observations (u_t, l_t, q) in target coordinates. In the common frame
///   u = R_t u_t,   l = m_t u_tᵀ(y − q) = uᵀ(T_s(p) − T_t(q)),
///   a_s = uᵀ ∂T_s(p)/∂X_s,   a_t = ∂l/∂X_t = −uᵀ ∂T_t(y)/∂X_t + (l / m_t) ∂m_t/∂X_t,
/// the exact derivatives with the rule's direction and foot held in target coordinates. For a
/// normal-distance rule (y − q ∥ u_t) a_t equals −uᵀ ∂T_t(q)/∂X_t; for LZD and ICP, whose
/// directions are not along y − q, the rotation columns must be taken at y.

#include <pcl_ls3d/adjustment/observation_set.h>
#include <pcl_ls3d/adjustment/overlap_grid.h>
#include <pcl_ls3d/adjustment/parameter_block.h>
#include <pcl_ls3d/rules/conjugate_rule.h>

#include <vector>

namespace pcl_ls3d {

/// \brief Finds observations for the current poses; keeps each source point's rule cache
///        between calls (the rules reuse local surface elements while a point barely moves).
///        Not thread-safe itself; parallel inside (OpenMP).
class PairMatcher
{
public:
  /// Which source points to look at in one call.
  struct Sampling
  {
    std::size_t every = 1;     ///< every k-th point only (coarse iterations)
    bool skip_missed = false;  ///< skip points that found no correspondence last time
  };

  /// Prepares a match of `source` (body coordinates reduced to the source block's input
  /// origin) against `target` with `rule`; correspondences farther than max_distance (target
  /// units) are none. With a finite max_distance, source points with no target point within
  /// reach are culled by a grid look-up before any search (overlap_grid.h). The target, the
  /// rule and the points must outlive the matcher's use.
  void
  reset(const std::vector<Eigen::Vector3d>& source, const TargetSurface& target, const ConjugateRule& rule,
        double max_distance);

  /// Observations of the sampled source points under the given poses.
  const ObservationSet&
  match(const BlockLinearization& source_pose, const BlockLinearization& target_pose,
        const Sampling& sampling);

  /// Changes the maximum correspondence distance for the next match() (the overlap grid is
  /// rebuilt when the reach changed by more than a quarter).
  void
  setReach(double max_distance);
  double
  reach() const
  {
    return max_distance_;
  }

  /// From now on every rule reuses exactly its cached element (the observation set stays
  /// fixed, so the last iterations converge instead of cycling between neighbouring elements).
  void
  freeze();

  /// \brief What a matcher remembers between calls: the rules' per-point caches and which
  ///        points found no correspondence. Saved and restored by a distributed strip
  ///        adjustment, whose match jobs are separate processes, so that every iteration sees
  ///        exactly the state a single process would.
  struct State
  {
    std::vector<CorrespondenceCache> caches;
    std::vector<unsigned char> missed;
  };
  State
  state() const
  {
    return {caches_, missed_};
  }
  /// Restores a state taken from a matcher reset() on the same points; false (nothing
  /// changed) when the sizes do not match.
  bool
  restore(State state);

  /// Drops the observations of the last match() whose keep flag is 0 (keep has one flag per
  /// observation; e.g. a wrapper's correspondence rejectors). Order is preserved.
  void
  keepOnly(const std::vector<char>& keep);

  /// The observations of the last match().
  const ObservationSet&
  observations() const
  {
    return set_;
  }
  /// a_s = uᵀ ∂T_s(p)/∂X_s of an observation, at the poses of the last match().
  RowVector7d
  sourceRow(const Observation& o) const;
  /// a_t = ∂l/∂X_t of an observation (see the file comment), at the poses of the last match().
  RowVector7d
  targetRow(const Observation& o) const;
  /// T_s(p): where the observed source point lies in the common frame.
  Eigen::Vector3d
  position(const Observation& o) const;
  /// The source point (reduced body coordinates) an observation belongs to.
  const Eigen::Vector3d&
  sourcePoint(const Observation& o) const
  {
    return (*source_)[static_cast<std::size_t>(o.point)];
  }
  /// True when the overlap grid culls points (finite max_distance).
  bool
  culling() const
  {
    return grid_.built();
  }

private:
  void
  matchPoint(std::size_t p, const BlockLinearization& source_pose, const BlockLinearization& target_pose,
             std::vector<Observation>& out);

  const std::vector<Eigen::Vector3d>* source_ = nullptr;
  const TargetSurface* target_ = nullptr;
  const ConjugateRule* rule_ = nullptr;
  double max_distance_ = 0.0;
  double grid_reach_ = 0.0;  ///< the reach the overlap grid was built for
  OverlapGrid grid_;
  std::vector<CorrespondenceCache> caches_;
  std::vector<unsigned char> missed_;             ///< no correspondence at the point's last search
  std::vector<std::vector<Observation>> chunks_;  ///< per block of points, concatenated in order
  ObservationSet set_;
  BlockLinearization source_pose_{ParameterBlock()}, target_pose_{ParameterBlock()};
};

}  // namespace pcl_ls3d
