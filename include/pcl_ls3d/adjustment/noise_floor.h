#pragma once
/// \file noise_floor.h
/// \brief Parameters whose information is no more than the noise of the surface normals.
///
/// The rank test of the solve (gauss_markov.h) passes the in-plane shifts and the rotation about
/// the normal on a noisy plane: the normals' noise makes their columns independent, so they come
/// out "determined" with a confident σ. Their information is no larger than what the noise alone
/// puts into the normal matrix. The noise floor M = Σ p E[δa δaᵀ] (δa: the change of a design row
/// when the observation's normal tilts by its measured noise σ_u) is that share; a parameter
/// direction whose generalised eigenvalue μ of M v = μ N v exceeds a share s gets less than
/// (1/s − 1) × its noise floor from real geometry, and is undeterminable.
/// Used by the pair engine and, per strip, by the strip adjustment.

#include <pcl_ls3d/adjustment/gauss_markov.h>
#include <pcl_ls3d/adjustment/observation_set.h>
#include <pcl_ls3d/adjustment/pair_matcher.h>
#include <pcl_ls3d/rules/target_surface.h>

#include <Eigen/Core>

#include <cstddef>
#include <utility>
#include <vector>

namespace pcl_ls3d {

/// Largest share of a direction's information that may come from the normals' noise: the pair
/// engine's σ_u (fittedNormalVariance) is the fits' own, so a direction is undeterminable when
/// the geometry gives it less information than the noise does (μ > 1/2); the strips' σ_u comes
/// from neighbouring observations, whose fits share points and agree better than the noise, so
/// their limit is lower.
constexpr double kPairNoiseShare = 1.0 / 2.0;
constexpr double kStripNoiseShare = 1.0 / 3.0;

/// Pairs (k, l) of observation indices whose normals should agree but for noise.
using NeighbourPairs = std::vector<std::pair<std::size_t, std::size_t>>;

/// Each point's first observation with the previous one in the set's order, when their
/// positions lie within `reach` (observations ordered along a grid, as the strips' are).
NeighbourPairs
sequentialNeighbours(const PairMatcher& matcher, const ObservationSet& set, double reach);

/// At most this many observations are looked at for a median.
constexpr std::size_t kNoiseAnchors = 1024;

/// σ_u² per tangent component of the target's normals, as a k-neighbour quadric fit at the
/// observations' feet determines them (the rules' default surface): the slopes' variance from the
/// fit's residual noise, median over up to kNoiseAnchors observations; 0 with fewer than 20.
/// Neighbouring observations' normals would underestimate it: their fits share most points.
double
fittedNormalVariance(const TargetSurface& target, const ObservationSet& set, int neighbours = 20);

/// σ_u² per tangent component of the observations' unit normals: for two neighbours on a smooth
/// surface the normals differ by noise (and by curvature, which only makes the estimate
/// conservative); var = median |Δu|² / (4 ln 2). 0 with fewer than 20 pairs.
double
normalNoiseVariance(const ObservationSet& set, const NeighbourPairs& neighbours);

/// M = Σ p_k var δa_k δa_kᵀ over both tangent tilts of each observation's normal; `row(o)` is the
/// caller's design row of an observation (any width).
template <typename RowOf>
auto
noiseFloor(const ObservationSet& set, const Eigen::VectorXd& weights, double var, const RowOf& row)
{
  using Row = decltype(row(set[0]));
  using Matrix = Eigen::Matrix<double, Row::ColsAtCompileTime, Row::ColsAtCompileTime>;
  Matrix M = Matrix::Zero();
  if (!(var > 0.0))
    return M;
  const double eps = 1e-4;
  for (std::size_t k = 0; k < set.size(); ++k) {
    const double w = weights[static_cast<Eigen::Index>(k)];
    const Observation& o = set[k];
    const double len = o.direction.norm();
    if (!(w > 0.0) || !(len > 0.0))
      continue;
    const Eigen::Vector3d u = o.direction / len;
    const Eigen::Vector3d t1 = u.unitOrthogonal(), t2 = u.cross(t1);
    const Row a = row(o);
    for (const Eigen::Vector3d& t : {t1, t2}) {
      Observation tilted = o;
      tilted.direction = (u + eps * t).normalized() * len;
      const Row da = (row(tilted) - a) / eps;
      M.template selfadjointView<Eigen::Upper>().rankUpdate(da.transpose(), w * var);
    }
  }
  M.template triangularView<Eigen::StrictlyLower>() = M.transpose();
  return M;
}

/// The free unknowns (finite a-priori weight) of one 7-parameter block that the noise floor M
/// dominates (generalised eigenvalue above `share`), given the block's normal matrix N (a-priori
/// weights added here) and the rank test's column scaling; flagged one at a time, the test
/// repeated without each.
std::vector<bool>
noiseDominated(const Matrix7d& N, const Matrix7d& M, const Vector7d& apriori_weights, const Vector7d& scaling,
               double share);

/// Holds the flagged unknowns at their start values for one solve (infinite a-priori weight).
void
holdAtStart(const std::vector<bool>& held, const Eigen::VectorXd& start, GaussMarkovProblem& problem);

/// After the solve: held unknowns are reported undeterminable, not fixed.
void
reportHeldUndeterminable(const std::vector<bool>& held, GaussMarkovSolution& sol);

}  // namespace pcl_ls3d
