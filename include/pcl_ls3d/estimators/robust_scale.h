#pragma once
/// \file robust_scale.h
/// \brief Scale estimates for robust estimation: the σ̂ that standardises residuals, u = v / σ̂,
///        and the tuning constants of the shipped estimators (in units of σ̂). PCL-free.
///
/// Tuning constants for Gaussian errors (Maronna, Martin & Yohai 2006, §2.3, §5.5; Huber 1981):
///   Huber k = 1.345 and Tukey c = 4.685: 95 % asymptotic efficiency of the M-estimate;
///   Tukey c = 1.5476 with b = 0.5 in the M-scale equation: 50 % breakdown of the S-estimate.

#include <Eigen/Core>

#include <cstddef>

namespace pcl_ls3d {

constexpr double kHuber95 = 1.345;    ///< Huber k for 95 % efficiency at the normal
constexpr double kTukey95 = 4.685;    ///< Tukey biweight c for 95 % efficiency at the normal
constexpr double kTukeyS50 = 1.5476;  ///< Tukey c of the 50 %-breakdown S-scale (b = 0.5)
/// Rousseeuw & Leroy's (1987, p. 202) reweighting cut after a high-breakdown fit: |v| > 2.5 ŝ is out.
constexpr double kReweightingCut = 2.5;

/// \brief Where an estimator takes σ̂ from.
enum class ScaleRule
{
  SIGMA0,  ///< σ̂0 of the previous Gauss–Markoff solve (eq. 11), as Zuo's eq. 15 and Baarda do
  MAD,     ///< 1.4826 · med |v − med v| of this iteration's residuals (Li et al. 2001, eq. 7)
  FIXED    ///< one value given beforehand (the S-scale of an MM-estimator's start)
};

/// "sigma0", "mad", "fixed".
const char*
toString(ScaleRule rule);

/// Li et al. 2001, eq. 7: 1.4826 · med |v_i − med v|. 0 for fewer than two values; non-finite
/// values are ignored.
double
madScale(const Eigen::Ref<const Eigen::VectorXd>& v);

/// Tukey's biweight ρ scaled to 1 beyond c: ρ(u) = 1 − (1 − (u/c)²)³ for |u| ≤ c, else 1.
double
tukeyRho(double u, double c);

/// \brief M-estimate of scale (the S-scale at a given fit): the s solving
///        (1/n) Σ ρ_c(v_i / s) = b with Tukey's ρ (Rousseeuw & Leroy 1987, §3.4; Maronna et al.
///        2006, §2.5), by the fixed-point iteration s² ← s² (1/(n b)) Σ ρ_c(v_i / s).
///        c = 1.5476, b = 0.5: breakdown 50 %, consistent for N(0, σ²).
/// \param[in] start first s (≤ 0: the MAD scale)
/// \return 0 when more than n(1 − b) residuals are exactly 0 or the input is empty
double
mScale(const Eigen::Ref<const Eigen::VectorXd>& v, double c = kTukeyS50, double b = 0.5, double start = 0.0);

/// LMS scale (Rousseeuw & Leroy 1987, p. 202): 1.4826 (1 + 5 / (n − p)) √(med v²).
double
lmsScale(double median_squared, std::size_t n, int p);

/// \brief The final scale of LMS (Rousseeuw & Leroy 1987, p. 202, eqs. 1.5.11–1.5.12): with the
///        preliminary s0 = lmsScale() of the LMS fit, weights w_i = 1 when |v_i| ≤ 2.5 s0 and 0
///        otherwise, σ* = √(Σ w_i v_i² / (Σ w_i − p)). One step, as the book defines it. 0 when
///        no more than p residuals lie inside.
double
lmsFinalScale(const Eigen::Ref<const Eigen::VectorXd>& v, double s0, int p);

/// \brief LTS scale: σ̂ = √(Σ_{i≤h} v²_(i) / h) / √(1 − 2 q φ(q) / α), with α = h / n and
///        q = Φ⁻¹((1 + α)/2), the consistency factor of the α-trimmed normal (Rousseeuw & Van
///        Driessen 2006). α = 0.5: σ̂ = 2.648 √(mean of the smaller half of v²).
double
ltsScale(double trimmed_mean_squared, double alpha);

/// \brief Reweighted (truncated) scale: starting from `start`, iterates
///          σ² ← Σ_{|v_i| ≤ c σ} v_i² / (n_in κ(c)),   κ(c) = 1 − 2 c φ(c) / (2Φ(c) − 1),
///        the consistency factor of the normal truncated at ±c (c = 2.5: κ = 0.911), until it
///        settles. From an inflated high-breakdown scale (LMS/LTS/S near 50 % contamination) it
///        descends to the σ of the observations that fit the estimate (Rousseeuw & Van Driessen's
///        reweighting step, iterated). 0 when no residual lies inside.
double
reweightedScale(const Eigen::Ref<const Eigen::VectorXd>& v, double start, double c = kReweightingCut);

/// σ̂ by a rule: σ0 (sigma0 ≤ 0 → MAD), the MAD of v, or `fixed`.
double
scaleByRule(ScaleRule rule, const Eigen::Ref<const Eigen::VectorXd>& v, double sigma0, double fixed);

}  // namespace pcl_ls3d
