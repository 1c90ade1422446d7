#pragma once
/// \file overlap_matcher.h
/// \brief Stage "match" of the strip adjustment for one overlap: the engine's PairMatcher in
///        each direction (points of strip i on strip j's surface and vice versa) with BOTH
///        strips' poses, the engine's ObservationWeighting with the chosen estimator, and the
///        14 × 14 normal equations of the rows [a_i | a_j]. The same code runs inside the
///        single-process adjustment and in a distributed match job (its matcher state is saved
///        and restored between the jobs of successive iterations).
///
/// Errors in variables: the observed point of the source strip is noisy and enters the scale
/// columns of both rows (the source's at the point, the target's at its image y); as in the
/// pair engine (errors_in_variables.h) both are evaluated at the adjusted point, which moves
/// a_s[m] by −c l and a_t[m] by +c l m_s / m_t.

#include <pcl_ls3d/adjustment/errors_in_variables.h>
#include <pcl_ls3d/adjustment/observation_weighting.h>
#include <pcl_ls3d/adjustment/pair_matcher.h>
#include <pcl_ls3d/estimators/robust_estimator.h>
#include <pcl_ls3d/strips/overlap_contribution.h>
#include <pcl_ls3d/strips/overlap_selection.h>

#include <pcl/kdtree/kdtree_flann.h>

#include <array>
#include <memory>

namespace pcl_ls3d {
namespace strips {

/// \brief Both directions of one overlap.
class OverlapMatcher
{
public:
  /// `selection` must outlive the matcher. `noise_i`, `noise_j`: the strips' own noise σ
  /// (errors-in-variables; 0 = none).
  OverlapMatcher(const OverlapSelection& selection, const ConjugateRule& rule,
                 const RobustEstimator& estimator, const StripAdjustmentSettings& settings, double noise_i,
                 double noise_j);

  /// Matches, weighs and accumulates one iteration at the poses of strips i and j.
  OverlapContribution
  contribute(const ParameterBlock& block_i, const ParameterBlock& block_j, const MatchInput& in);

  /// Final evaluation at the adjusted poses: the contribution with the precision cells of
  /// edge `cell` (block coordinates).
  OverlapContribution
  evaluate(const ParameterBlock& block_i, const ParameterBlock& block_j, const MatchInput& in, double cell);

  /// The matchers' memory (forward, backward), for a distributed run.
  std::array<PairMatcher::State, 2>
  state() const;
  bool
  restore(std::array<PairMatcher::State, 2> state);

private:
  struct Direction;
  static Matrix14d
  noiseFloor(const Direction& D, const ObservationSet& set, const Eigen::VectorXd& p);
  OverlapContribution
  run(const ParameterBlock& block_i, const ParameterBlock& block_j, const MatchInput& in, double cell);

  const StripAdjustmentSettings& settings_;
  const ConjugateRule& rule_;
  const RobustEstimator& estimator_;
  std::array<std::unique_ptr<Direction>, 2> dir_;

public:
  ~OverlapMatcher();
};

/// True when the adjustment matches this direction of an overlap: the forward one (points of
/// strip i on j), the backward one only with `both_directions`, and either only when it has at
/// least `min_overlap_observations` observed points and a target surface.
bool
directionWanted(const DirectionSelection& selection, bool forward, const StripAdjustmentSettings& settings);

/// σ of a strip's own noise from its stable points (local quadrics, errors_in_variables.h).
double
stripNoise(const pcl::PointCloud<pcl::PointXYZ>& stable_points, double density);

}  // namespace strips
}  // namespace pcl_ls3d
