#pragma once
/// \file overlap_contribution.h
/// \brief What a match job sends back for one overlap (i, j) in one iteration: the normal
///        equations of its observations in both directions with rows [a_i | a_j] (strip i's
///        pose against strip j's: each observation ties two strips), and the counts the report
///        and the solver need. In the
///        final evaluation pass also the spatial score cells of the precision estimate.

#include <pcl_ls3d/adjustment/normal_equations.h>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace strips {

using Vector14d = Eigen::Matrix<double, 14, 1>;
using Matrix14d = Eigen::Matrix<double, 14, 14>;

/// \brief The observations of one 3-D cell of the spatial precision estimate, for one
///        overlap: S = Σ p v [a_i | a_j]ᵀ and N = Σ p aᵀa (upper triangle).
struct PrecisionCell
{
  std::int32_t x = 0, y = 0, z = 0;  ///< cell indices (block coordinates / cell edge)
  Vector14d score = Vector14d::Zero();
  Matrix14d normal = Matrix14d::Zero();
};

/// \brief What one iteration's match needs besides the poses.
struct MatchInput
{
  int iteration = 1;
  bool coarse = false;                ///< observe about coarse_observations points per direction
  bool frozen = false;                ///< correspondences frozen (the matchers' caches are reused as is)
  double sigma0 = 0.0;                ///< σ0 of the previous solve (≤ 0 before the first)
  Matrix14d qxx = Matrix14d::Zero();  ///< Qxx block of (i, j) of the previous solve
  bool scale_free = false;  ///< m is estimated (or tested): apply the errors-in-variables correction
};

/// \brief One direction's counts.
struct DirectionCounts
{
  std::size_t observations = 0;  ///< conjugate points found
  std::size_t used = 0;          ///< with weight > 0
  double vtpv = 0.0;             ///< Σ p l² at the poses of the match
  double robust_scale = 0.0;     ///< 1.4826 · median |l| of the observations
  /// Σ p σ²_surface over the used observations: the variance of the conjugate surface at the
  /// query (the rule's local fit, e.g. LND's quadric height), which σ0 contains besides the
  /// observed point's own noise.
  double surface_variance = 0.0;
};

/// \brief One overlap's contribution to one iteration.
struct OverlapContribution
{
  int overlap = -1;    ///< index into the plan's overlap list
  int i = -1, j = -1;  ///< strips
  int iteration = 0;
  double spacing = 0.0;        ///< thinning cell edge of the overlap's observations
  PairNormalEquations normal;  ///< rows [a_i | a_j], both directions summed
  /// What noise in the conjugate surfaces' normals alone puts into normal.N: Σ p E[δa δaᵀ]
  /// with δa the change of a row under a normal tilted by its measured noise σ_u. On a flat
  /// overlap the horizontal parameters' information is no larger than this noise floor, so
  /// they are undeterminable however small the rank test finds their pivots.
  Matrix14d noise_floor = Matrix14d::Zero();
  DirectionCounts forward, backward;
  std::vector<PrecisionCell> cells;  ///< final evaluation only
};

}  // namespace strips
}  // namespace pcl_ls3d
