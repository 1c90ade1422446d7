#pragma once
/// \file spatial_precision.h
/// \brief Honest precision for surface matching, where observations are not independent.
///
/// Why σ0 √q_ii (eq. 14) is too small here: an observation's error has two parts, the source
/// point's own noise (independent between observations) and the error of the local target
/// surface it is measured to. Every target point enters the local surfaces of all source points
/// around it (a 12-point fit at equal densities is shared by ~12 observations), so the target
/// part is correlated over a neighbourhood: Σ_ll = σ_s² I + Σ_t with Σ_t non-diagonal, while
/// eq. 14 assumes Σ_ll = σ0² I. Measured (100 m pairs, 1 pt/m², 5 cm noise, LND): target noise
/// alone gives a parameter spread 1.6–2.5 × σ0 √q_ii; source noise alone 0.8–1.1 ×.
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

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace pcl_ls3d {

/// \brief Accumulates per-observation scores into cells and forms the HAC middle term.
class SpatialScoreSum
{
public:
  explicit SpatialScoreSum(double cell) : inv_cell_(1.0 / cell) {}

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

/// \brief Robust estimate of the isotropic noise σ of a sampled smooth surface: local quadrics
///        fitted to the points within `radius` of up to max_seeds seed points (spread over
///        `seeds`), pooled as the median of RSS/(k − 6) corrected to a mean. Returns 0 when no
///        seed has enough neighbours. Surface roughness (vegetation, edges) counts as noise, so
///        it is an upper bound on rough ground.
double
estimateSurfaceNoise(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& seeds,
                     double radius, std::size_t max_seeds = 256);

}  // namespace pcl_ls3d
