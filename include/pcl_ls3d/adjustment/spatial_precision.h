#pragma once
/// \file spatial_precision.h
/// \brief Honest precision for surface matching, where observations are not independent.
///
/// Why σ0 √q_ii (eq. 14) is too small here: an observation's error has two parts, the source
/// point's own noise (independent between observations) and the error of the local target
/// surface it is measured to. Every target point enters the local surfaces of all source points
/// around it (a 12-point fit at equal densities is shared by ~12 observations), so the target
/// part is correlated over a neighbourhood: Σ_ll = σ_s² I + Σ_t with Σ_t non-diagonal, while
/// eq. 14 assumes Σ_ll = σ0² I, and the formal σ0 √q_ii is too small (measured in
/// docs/LS3D_PRECISION.md).
///
/// The covariance of the least-squares estimate X̂ = −Q AᵀP L under any Σ_ll is the sandwich
/// C = Q (AᵀP Σ_ll P A) Q. The middle term is estimated from the residuals with a spatial
/// Bartlett kernel (a spatial HAC estimator, Conley 1999): with s_i = p_i v_i a_iᵀ summed over
/// cubic cells of edge h, M is the average over the 8 grids of 2h blocks shifted by h of
/// Σ_B S_B S_Bᵀ, i.e. Σ_c Σ_{c' adjacent or equal} w(c, c') S_c S_c'ᵀ with w = Π_axes (1 − |Δ|/2),
/// positive semi-definite. Pairs closer than ~h count with weight ≥ ½; h must exceed the
/// correlation length (the rule's neighbourhood diameter). Each block score is corrected for the
/// block's own leverage (S_B → (I − N_B Q)⁻¹ S_B, a block jackknife / CR3 form), because
/// Σ_i a_i v_i = 0 makes the plain estimator too small when blocks are few. Without
/// correlation M → σ0² AᵀPA and C → σ0² Q, eq. 14. Derivation and measurements:
/// docs/LS3D_PRECISION.md.

#include <pcl_ls3d/common/similarity_transform.h>

#include <Eigen/Core>

#include <array>
#include <cmath>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace pcl_ls3d {

/// \brief Accumulates per-observation scores into cells and forms the HAC middle term.
class SpatialScoreSum
{
public:
  explicit SpatialScoreSum(double cell) : inv_cell_(1.0 / cell)
  {}

  /// Adds an observation at position x with design row a (weight p) and score s = p v aᵀ.
  void
  add(const Eigen::Vector3d& x, const Vector7d& a, double p, const Vector7d& score);

  /// The average over the 8 grids of 2 × 2 × 2-cell blocks shifted by one cell of
  /// Σ_B S*_B S*_Bᵀ (without the n/(n−u) factor). With q = nullptr, S*_B = S_B (the Bartlett
  /// form in the file comment); with the cofactor matrix Q, the block-jackknife (CR3) correction
  /// S*_B = (I − N_B Q)⁻¹ S_B, N_B = Σ_{i∈B} p_i a_iᵀa_i: the residuals of a block are shrunk by
  /// its own leverage (Σ_i a_i v_i = 0 over all data), which biases the plain estimator low when
  /// blocks are few (push-through form of (I − H_BB)⁻¹ v_B, Bell & McCaffrey 2002).
  Matrix7d
  meat(const Matrix7d* q = nullptr) const;

  std::size_t
  cells() const
  {
    return cells_.size();
  }

private:
  struct Cell
  {
    Vector7d score = Vector7d::Zero();
    Matrix7d normal = Matrix7d::Zero();
  };
  double inv_cell_;
  std::unordered_map<std::uint64_t, Cell> cells_;
};

/// \brief \a sandwich with no variance below the formal one, \a formal = σ0² Q (eq. 14): the
///        spatially correlated part of the errors can only add to what independent errors give;
///        a sandwich below eq. 14 comes from too few blocks to estimate the middle term (a 36 m
///        patch at h = 9.3 m holds 2 × 2 blocks per grid, and its σ came out 2.4–2.8 × too small,
///        docs/BENCHMARKS.md "Gentle terrain"). Scaled as C' = D C D with D = diag(max(1,
///        √(F_ii / C_ii))), so the sandwich's correlations stay; fixed (0) and undeterminable
///        (non-finite) entries are left alone.
template <typename Matrix>
Matrix
notBelowFormal(const Matrix& sandwich, const Matrix& formal)
{
  Matrix out = sandwich;
  for (Eigen::Index i = 0; i < out.rows(); ++i) {
    const double c = sandwich(i, i), f = formal(i, i);
    if (!(c > 0.0) || !std::isfinite(c) || !std::isfinite(f) || f <= c)
      continue;
    const double d = std::sqrt(f / c);
    out.row(i) *= d;
    out.col(i) *= d;
  }
  return out;
}

/// \brief The middle term M of the sandwich: the CR3-corrected spatial sum of the scores
///        (SpatialScoreSum::meat(&qxx)) plus σ0² p_e for soft a-priori observations (finite
///        weight p_e on a determinable parameter), which are independent of the data.
///        `observation(j, x, a, p, v)` fills position x, design row a, weight p and residual v
///        of observation j < m (false: skip). Columns of parameters that were not estimated
///        (zero in qxx) hold their scores corrected for the estimated ones' leverage, which a
///        score test of held-out parameters uses (omitted_parameters.h).
template <typename ObservationFn>
Matrix7d
spatialMiddleTerm(std::size_t m, double cell, const Matrix7d& qxx, double sigma0,
                  const Vector7d& apriori_weights, const std::array<bool, 7>& determinable,
                  ObservationFn observation)
{
  SpatialScoreSum scores(cell);
  Eigen::Vector3d x;
  Vector7d a;
  double p = 0.0, v = 0.0;
  for (std::size_t j = 0; j < m; ++j)
    if (observation(j, x, a, p, v) && p > 0.0)
      scores.add(x, a, p, (p * v) * a);
  Matrix7d meat = scores.meat(&qxx);
  for (int i = 0; i < 7; ++i)
    if (determinable[static_cast<std::size_t>(i)] && apriori_weights[i] > 0.0 &&
        std::isfinite(apriori_weights[i]))
      meat(i, i) += sigma0 * sigma0 * apriori_weights[i];
  return meat;
}

/// \brief The sandwich covariance C = Q M Q of the parameters (M: spatialMiddleTerm()), at
///        least σ0² Q (notBelowFormal()).
template <typename ObservationFn>
Matrix7d
spatialSandwichCovariance(std::size_t m, double cell, const Matrix7d& qxx, double sigma0,
                          const Vector7d& apriori_weights, const std::array<bool, 7>& determinable,
                          ObservationFn observation)
{
  const Matrix7d meat = spatialMiddleTerm(m, cell, qxx, sigma0, apriori_weights, determinable, observation);
  return notBelowFormal<Matrix7d>(qxx * meat * qxx, sigma0 * sigma0 * qxx);
}

}  // namespace pcl_ls3d
