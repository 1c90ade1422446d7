#pragma once
/// \file errors_in_variables.h
/// \brief The source coordinates are noisy and enter the design matrix: the scale column
///        a_m = uᵀ R x carries the noise uᵀR e that is also in the observation (m uᵀR e), so
///        cov(a_m, l) = m σ_s² |u|² and E[AᵀPL] ≠ 0 at the truth, which biases m by about
///        −σ_s² / mean((uᵀRx)²) (rotation columns: uᵀ (∂R/∂φ) Rᵀ u = 0, no bias). Evaluating
///        the column at the adjusted source point of a Gauss–Helmert linearisation,
///        a_m' = a_m − c l with c = m σ_s² |u|² / var(l), var(l) = m² σ_s² |u|² + σ_t²,
///        removes the correlation. See docs/LS3D_PRECISION.md.

#include <pcl_ls3d/adjustment/surface_noise.h>

#include <Eigen/Core>

#include <algorithm>

namespace pcl_ls3d {

/// \brief The per-iteration factor of the scale-column correction.
class ScaleColumnCorrection
{
public:
  /// σ_s of the source (≤ 0: no correction).
  void
  setSourceNoise(double sigma_s)
  {
    sigma_s_ = sigma_s;
  }
  double
  sourceNoise() const
  {
    return sigma_s_;
  }

  /// Prepares an iteration at scale m with the previous σ0 and mean |u|² of the observations;
  /// the target part is σ_t² = σ0² − m² σ_s² mean|u|² (≥ 0). False (inactive) without σ_s or σ0.
  bool
  update(double m, double sigma0, double mean_u2)
  {
    active_ = sigma_s_ > 0.0 && sigma0 > 0.0;
    if (!active_)
      return false;
    ms2_ = m * sigma_s_ * sigma_s_;
    m2s2_ = m * ms2_;
    vt_ = std::max(0.0, sigma0 * sigma0 - m2s2_ * mean_u2);
    active_ = m2s2_ * mean_u2 + vt_ > 0.0;
    return active_;
  }
  bool
  active() const
  {
    return active_;
  }

  /// c of an observation with gradient norm² u2 (0 when inactive): a_m' = a_m − c l.
  double
  coefficient(double u2) const
  {
    return active_ ? ms2_ * u2 / (m2s2_ * u2 + vt_) : 0.0;
  }

private:
  double sigma_s_ = 0.0;
  double ms2_ = 0.0, m2s2_ = 0.0, vt_ = 0.0;
  bool active_ = false;
};

}  // namespace pcl_ls3d
