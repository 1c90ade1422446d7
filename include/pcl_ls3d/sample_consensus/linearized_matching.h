#pragma once
/// \file linearized_matching.h
/// \brief The frozen observation set a sample-consensus search works on (docs/ARCHITECTURE.md,
///        "Robust estimation and LMS"): every epoch point matched once to the reference surface
///        at a linearisation point X0 (the engine's pair matcher and rule), its design row
///        a_j = uᵀ ∂T(p)/∂X and its distance l_j kept. A subset is fitted by the engine's
///        Gauss–Markoff solve over the subset's rows (LHD on the sampled points, one Gauss–Newton
///        step from X0), and any estimate X is scored by the linearised residuals
///          v_j(X) = l_j + a_j (X − X0)                (Zuo et al. 2012, eq. 12 at X)
///        which cost 7 multiply-adds per observation, no neighbour search. The callers
///        re-linearise (relinearize(X̂)) when X̂ has moved far from X0. PCL-free; fit() and
///        residuals() are const and thread-safe.

#include <pcl_ls3d/adjustment/adjustment_report.h>
#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/adjustment/gauss_markov.h>
#include <pcl_ls3d/adjustment/pair_matcher.h>
#include <pcl_ls3d/adjustment/parameter_block.h>
#include <pcl_ls3d/rules/conjugate_rule.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl_ls3d {

/// \brief Matched observations of all epoch points, linearised at X0.
class LinearizedMatching
{
public:
  using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor>;

  /// \brief Frames and first match. The source block's input origin is the centroid of the
  ///        epoch points whose image under `guess` falls over the reference's extent; its
  ///        output origin is their image (as the engine's pair set-up). The settings give the
  ///        parameter model (a-priori weights), the correspondence distance and the rank test.
  /// \return false (and `why`, `failure`) when no point overlaps or no point found a conjugate:
  ///         NO_OVERLAP, or TOO_FEW_OBSERVATIONS when the reference is degenerate (collinear or
  ///         coincident) where the points lie over it, as the engine's pair adjustment says
  bool
  reset(const std::vector<Eigen::Vector3d>& points, const TargetSurface& reference, const ConjugateRule& rule,
        const AdjustmentSettings& settings, const Eigen::Matrix4d& guess, std::string* why = nullptr,
        TerminationType* failure = nullptr);

  /// Matches every point again at X (reduced frame) and makes X the linearisation point.
  /// False when no observation is left.
  bool
  relinearize(const Vector7d& X);

  /// Parameters (reduced frame) of a 4×4 transformation in the points' own coordinates.
  Vector7d
  parametersOf(const Eigen::Matrix4d& T) const;
  /// The 4×4 transformation (points' own coordinates → reference coordinates) of X.
  Eigen::Matrix4d
  matrixOf(const Vector7d& X) const;

  /// \brief Least-squares fit over the observations `obs` (indices into the set) with unit
  ///        weights: X = X0 + dx (eq. 10). False when the subset leaves a free parameter
  ///        undeterminable (rank test), has fewer observations than free parameters, or the solve fails.
  bool
  fit(const int* obs, std::size_t count, Vector7d& X) const;

  /// \brief Weighted fit over all observations (weights in [0, 1]); `solution` (optional)
  ///        receives σ0, Qxx and the redundancy. False as fit().
  bool
  fitWeighted(const Eigen::VectorXd& weights, Vector7d& X, GaussMarkovSolution* solution = nullptr) const;

  /// v = l + A (X − X0) for every observation.
  void
  residuals(const Vector7d& X, Eigen::VectorXd& v) const;
  /// Per epoch point the entry of v (one per observation) of its first observation (its normal
  /// or height distance for LND / LZD, the first axis for ICP); NaN for a point without one.
  std::vector<double>
  pointResiduals(const Eigen::VectorXd& v) const;
  /// v_j of one observation.
  double
  residual(std::size_t j, const Vector7d& X) const
  {
    return l_[static_cast<Eigen::Index>(j)] +
           rows_.row(static_cast<Eigen::Index>(j)).dot((X - x0_).transpose());
  }

  /// Number of observations m.
  std::size_t
  size() const
  {
    return static_cast<std::size_t>(l_.size());
  }
  /// Observation of epoch point i (its first one when a rule gives several), −1 when none.
  int
  observationOf(int point) const
  {
    return point >= 0 && static_cast<std::size_t>(point) < first_.size()
               ? first_[static_cast<std::size_t>(point)]
               : -1;
  }
  /// Observations of epoch point i: [observationOf(i), observationOf(i) + countOf(i)).
  int
  countOf(int point) const
  {
    return point >= 0 && static_cast<std::size_t>(point) < count_.size()
               ? count_[static_cast<std::size_t>(point)]
               : 0;
  }
  /// The observation records (point, direction u, distance l at X0, foot, surface variance).
  const ObservationSet&
  observations() const
  {
    return matcher_.observations();
  }
  /// Design rows a_j at X0 (m × 7, row-major) and distances l_j.
  const RowMatrix&
  rows() const
  {
    return rows_;
  }
  const Eigen::VectorXd&
  distances() const
  {
    return l_;
  }
  /// The linearisation point X0 (reduced frame).
  const Vector7d&
  linearizationPoint() const
  {
    return x0_;
  }
  /// The source block (origins, a-priori observations) of the reduced frame.
  const ParameterBlock&
  block() const
  {
    return block_;
  }
  /// Free (not fixed) parameters: the smallest sample that can determine them.
  int
  freeParameters() const;
  /// The epoch points reduced to the block's input origin.
  const std::vector<Eigen::Vector3d>&
  reducedPoints() const
  {
    return reduced_;
  }

private:
  void
  rebuildRows();

  std::vector<Eigen::Vector3d> reduced_;
  PairMatcher matcher_;
  ParameterBlock block_, target_block_;
  GaussMarkovProblem problem_;
  Vector7d x0_ = identityParameters();
  RowMatrix rows_;
  Eigen::VectorXd l_;
  std::vector<int> first_, count_;
};

}  // namespace pcl_ls3d
