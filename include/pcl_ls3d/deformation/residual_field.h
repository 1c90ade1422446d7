#pragma once
/// \file residual_field.h
/// \brief Per-point residuals of an epoch against the reference after robust matching, with
///        their σ and a significance flag (Li et al. 2001: deformed parts are the outliers of the
///        matching). PCL-free.
///
/// Every epoch point is matched once more at the final transformation with the matching's rule:
///   r_i = uᵀ(T(p_i) − q_i)       signed distance along the rule's direction (LZD: the height
///                                difference z − z_ref, positive = the epoch is higher; LND:
///                                along the reference's normal)
///   σ_i² = σ̂_e² + σ²_surf,i + a_i C a_iᵀ
/// with σ̂ the robust scale of the matching, σ²_surf,i the variance of the reference's local
/// surface fit at q_i (from the rule), σ̂_e² = max(σ̂² − med σ²_surf, 0) the epoch's own share of
/// σ̂ (so that on average σ_i² ≈ σ̂² but rough spots get a larger σ), and a_i C a_iᵀ the
/// transformation's covariance C propagated to the point (a_i its design row).
/// Significance:
///   SIGMA_K  |r_i| > k σ_i (k = 3, Li et al. 2001's 3σ criterion);
///   LOD95    an M3C2-style level of detection (Lague et al. 2013) on the mean of the k nearest
///            epoch residuals: |r̄_i| > LoD95_i = 1.96 (√(s_i² / n_i) + reg_i), s_i the spread of
///            those residuals, reg_i = √(a_i C a_iᵀ); residual and sigma then hold r̄_i and
///            √(s_i²/n_i) + reg_i.

#include <pcl_ls3d/adjustment/adjustment_report.h>
#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/rules/conjugate_rule.h>

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace deformation {

/// \brief How a residual is declared significant.
enum class DetectionRule
{
  SIGMA_K,  ///< |r| > k σ (Li et al.)
  LOD95     ///< M3C2-style level of detection at 95 % on the k-nearest-neighbour mean
};

/// "sigma_k", "lod95".
const char*
toString(DetectionRule rule);

/// \brief Settings of the residual field.
struct ResidualSettings
{
  DetectionRule rule = DetectionRule::SIGMA_K;
  double k = 3.0;           ///< SIGMA_K: significance factor
  int lod_neighbours = 12;  ///< LOD95: epoch points averaged around each point (itself included)
  /// Conjugate points farther than this are none (the matching's max correspondence distance).
  double max_distance = std::numeric_limits<double>::max();

  bool
  isValid(std::string* why = nullptr) const;
};

/// \brief One record per epoch point, in the epoch's order.
struct ResidualField
{
  std::vector<double> residual;            ///< r_i (NaN: no conjugate on the reference)
  std::vector<double> sigma;               ///< σ_i (NaN: no conjugate)
  std::vector<std::uint8_t> significant;   ///< 1 when |r| exceeds its threshold
  std::vector<Eigen::Vector3d> direction;  ///< u_i (reference frame; zero when none)
  std::size_t observed = 0;                ///< points with a residual
  std::size_t significant_count = 0;
  double scale = 0.0;                 ///< σ̂ used
  double median_surface_sigma = 0.0;  ///< √med σ²_surf
};

/// \brief Residuals of `points` (epoch coordinates, NaN allowed) at the matching's final
///        transformation `matching.transformation`, with σ from `scale` and `matching.covariance`.
/// \param[in] rule the matching's rule (prepared on `reference`)
ResidualField
computeResidualField(const std::vector<Eigen::Vector3d>& points, const TargetSurface& reference,
                     const ConjugateRule& rule, const AdjustmentReport& matching, double scale,
                     const ResidualSettings& settings);

}  // namespace deformation
}  // namespace pcl_ls3d
