#pragma once
/// \file robust_matching.h
/// \brief Robust surface matching in one call (Li et al. 2001), on the LS3D engine:
///
///   1. all-points least squares (LHD = LZD rule, 6 parameters, by default) from the guess,
///      to bring the surfaces close (Li: "an LHD matching using all matchable points is always
///      performed ... before the LMS estimator is applied");
///   2. for a weight-function estimator (Zuo, Huber, Tukey "M", "M-D"): IRLS from there in the
///      engine's Gauss–Markoff loop;
///      for LMS: m random p-subsets (eq. 12), the one minimising med v² (eq. 11), re-linearised
///      and searched again while the estimate moves; then Li's M-estimator (Tukey c = 4.685)
///      with its scale fixed from the LMS fit (Rousseeuw & Leroy's σ*, see LmsScale);
///      for MM (beyond the paper): FAST-LTS starts with C-steps, a scale fixed from the LTS fit
///      (reweighted, or the 50 %-breakdown S-scale), then a Tukey M-step at 95 % efficiency
///      holding out the points beyond 2.5 ŝ of the start while they stay there; a second
///      start from blocks of the surface is searched and reported (block_trimmed_squares.h);
///      both fixed scales at most the neighbour-difference noise of that fit (beyond the paper);
///   3. the report of the last adjustment: parameters with the engine's σ (spatial sandwich),
///      weights, residuals and redundancy numbers, σ̂, subsets, rounds and why it stopped.
/// PCL-free; the PCL face is sample_consensus/sac_model_surface_matching.h.

#include <pcl_ls3d/adjustment/adjustment_report.h>
#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/estimators/robust_estimator.h>
#include <pcl_ls3d/rules/conjugate_rule.h>
#include <pcl_ls3d/sample_consensus/subset_search.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {

/// \brief The estimators of robust matching.
enum class RobustMethod
{
  LEAST_SQUARES,  ///< plain LHD (breakdown 0)
  ZUO,            ///< Zuo's 0/1 weight at K σ0 (eq. 15 of Zuo 2012)
  HUBER,          ///< Huber, k = 1.345, MAD scale
  M,              ///< Li's M: Tukey biweight, c = 4.685, MAD scale (eqs. 6–8)
  MD,             ///< Li's M-D (GM): Tukey on Baarda's normalised residual (eq. 10)
  LMS,            ///< Li's LMS: subsets (eqs. 11–12), then the M-estimator
  MM              ///< LTS with C-steps, fixed scale, Tukey M-step at 95 % efficiency
};

/// "ls", "zuo", "huber", "m", "md", "lms", "mm".
const char*
toString(RobustMethod method);
/// Parses the names of toString() (case-insensitive; "m-d", "gm", "tukey", "least-squares"
/// accepted); false when unknown.
bool
parseRobustMethod(const std::string& text, RobustMethod& method);

/// \brief The scale an MM-estimator fixes for its M-step.
enum class MmScale
{
  REWEIGHTED,  ///< the LTS scale refined by reweighting at 2.5 σ̂ (robust_scale.h, default)
  S_SCALE      ///< the textbook choice: M-scale of the LTS residuals (c = 1.5476, b = 0.5)
};

/// \brief The scale LMS's M-step (Li: "an M-estimator is finally applied to improve the
///        precision of the LMS estimates") standardises its residuals with.
///
/// Li et al. give one scale for M-estimators, eq. 7, 1.4826 · MAD of the residuals of the
/// current fit, stated for the M-estimator on its own. Used after LMS it is recomputed from
/// all residuals each iteration, and the deformed part (up to half of them) inflates it: at
/// 36 % deformed by 5 σ the MAD is ≈ 2 σ, Tukey's c = 4.685 then keeps weight up to ≈ 9 σ and
/// the deformation pulls the M-step away from the LMS fit. Rousseeuw & Leroy (1987, p. 202)
/// take the scale of the LMS fit instead: s0 = 1.4826 (1 + 5/(n − p)) √med v², then σ* from the
/// residuals within 2.5 s0 (lmsFinalScale()), fixed for the reweighted step.
enum class LmsScale
{
  FINAL,        ///< σ* of the LMS fit (Rousseeuw & Leroy's reweighted scale; default)
  PRELIMINARY,  ///< s0 of the LMS fit (inflated when much of the surface moved)
  MAD           ///< eq. 7 on all residuals, every iteration (the reading before issue 9 pt 2)
};

/// \brief Settings of robustMatching().
struct RobustMatchingSettings
{
  RobustMethod method = RobustMethod::LMS;
  /// The adjustment of every stage (parameter model, iterations, ...). Default: 6 parameters.
  AdjustmentSettings adjustment = AdjustmentSettings::rigid6();
  /// Tuning constant of the weight function (K, k or c in σ̂ units; NaN: the estimator's default).
  double constant = std::numeric_limits<double>::quiet_NaN();

  // --- high-breakdown search (LMS, MM) ---------------------------------------------------------
  int subsets = 0;                   ///< m; 0: defaultSubsets(contamination, sample_size)
  double contamination = 0.5;        ///< ε of eq. 12: the share of the surface that may have moved
  int sample_size = 7;               ///< p (Li: 7 for 6 parameters)
  std::size_t score_points = 20000;  ///< rank subsets on a random subsample of this many
  std::uint32_t seed = 1;
  int max_rounds = 3;  ///< search rounds (re-linearised at the last estimate)
  MmScale mm_scale = MmScale::REWEIGHTED;
  /// MM: points beyond 2.5 ŝ of the LTS start stay out of the M-step (Rousseeuw & Leroy's
  /// reweighting, MaskedEstimator). Tukey's c = 4.685 ŝ keeps a deformation of c σ near 4–5 σ
  /// partly weighted, and that pull leads the M-step from a start 0.1 σ off to a compromise
  /// 5 σ off (42 % deformed by 5 σ); held out, it cannot pull.
  bool mm_hold_out_beyond_start = true;
  /// LMS and MM: also search a start on blocks of the surface (block_trimmed_squares.h),
  /// reported as block_start_transformation for the deformation analysis to refine and choose
  /// between (deformation/start_choice.h; on there by default); robust matching itself continues
  /// from its own subset fit, so other callers leave it off.
  bool block_start = false;
  LmsScale lms_scale = LmsScale::FINAL;
  /// LMS and MM: the M-step's fixed scale is at most σ_d, the noise of neighbouring residuals at
  /// the high-breakdown fit (neighbour_noise.h). A fit that compromises between the stable and
  /// the moved part inflates its own scale (σ* 1.5 σ at 25 % deformed by 4 σ), Tukey's
  /// c = 4.685 σ̂ then keeps half the deformation's weight and the M-step stays at the
  /// compromise; the deformation is gathered, so the differences of neighbours see the noise
  /// alone. false: the fit's own scale (Rousseeuw & Leroy's, as Li et al.).
  bool cap_scale_by_neighbour_noise = true;
  /// When false the guess is taken as the all-points least-squares start (already computed by
  /// the caller) and stage 1 is skipped; report.start then stays NOT_RUN.
  bool least_squares_start = true;
  /// LMS and MM: the final fit is UNRELIABLE when the scale of the residuals its M-step kept
  /// (1.4826 · med |v| over the observations with weight > 0) exceeds this multiple of σ_d, the
  /// noise of neighbouring residuals at that fit (neighbour_noise.h). A fit that compromises
  /// between the stable and the moved part keeps a tilted stable part and some of the patch:
  /// LMS at 25 % deformed by 4 σ ended CONVERGED 2.4–2.9 σ off with the kept scale 1.3–1.5 σ_d.
  /// On Li's 50 × 50 grid (16, 25, 36 % × 3.5–7 σ × 9 positions × 3 seeds) no successful trial
  /// of LMS or MM was above 1.43, and 1.5 refused 65 of the 148 LMS fits more than 2 σ off
  /// (docs/HONESTY_API.md). Off (0) by default: on denser surfaces σ_d underestimates the noise
  /// (neighbouring residuals share the reference's local surface), so right fits would be
  /// refused there. 0: off.
  double max_kept_scale_ratio = 0.0;

  /// The number of subsets that will be drawn.
  int
  subsetCount() const
  {
    if (subsets > 0)
      return subsets;
    // FAST-LTS (MM) concentrates every start by C-steps: 500 starts as Rousseeuw & Van Driessen.
    return method == RobustMethod::MM ? 500 : defaultSubsets(contamination, sample_size);
  }
  /// True when usable; otherwise `why` says which field is wrong.
  bool
  isValid(std::string* why = nullptr) const;
};

/// \brief Everything robust matching produced.
struct RobustMatchingReport
{
  RobustMethod method = RobustMethod::LMS;
  std::string estimator;  ///< e.g. "lms(3000 subsets) + tukey(4.685)"
  TerminationType termination = TerminationType::NOT_RUN;
  std::string message;  ///< why it stopped, warnings
  /// The final adjustment: parameters (reduced frame), transformation (cloud coordinates),
  /// σ0, σ_i (spatial sandwich), Qxx, per-observation residuals, weights and redundancy
  /// numbers, iteration log.
  AdjustmentReport adjustment;
  AdjustmentReport start;  ///< the all-points least-squares start
  double scale = 0.0;      ///< σ̂ the final weights standardise with
  /// High-breakdown stage (LMS, MM): the last round's search, its estimate and scale.
  SubsetSearchResult search;
  int rounds = 0;         ///< search rounds (re-linearisations + 1)
  int subsets_drawn = 0;  ///< over all rounds
  Eigen::Matrix4d high_breakdown_transformation = Eigen::Matrix4d::Identity();
  double high_breakdown_scale = 0.0;  ///< the scale the M-step keeps fixed (LMS: σ* or s0, MM: see MmScale)
  double neighbour_noise = 0.0;       ///< σ_d of the high-breakdown fit's residuals (neighbour_noise.h)
  /// LMS / MM with block_start: the block-LTS estimate (4×4, as the transformation) and the share
  /// of the observations in the blocks its criterion kept; support 0: not searched.
  Eigen::Matrix4d block_start_transformation = Eigen::Matrix4d::Identity();
  double block_support = 0.0;
  std::size_t held_out = 0;  ///< MM: points beyond 2.5 ŝ of the start, out of the M-step
  /// LMS, MM: 1.4826 · med |v| of the observations the final M-step kept, and σ_d of the
  /// final residuals (RobustMatchingSettings::max_kept_scale_ratio); 0: not measured.
  double kept_scale = 0.0;
  double final_neighbour_noise = 0.0;
  int iterations = 0;  ///< adjustment iterations over all stages

  /// Usable estimate (the final adjustment converged or hit its iteration limit).
  bool
  isSolutionUsable() const
  {
    return adjustment.isSolutionUsable();
  }
  /// One line: method, termination, σ̂, subsets, iterations.
  std::string
  brief() const;
};

/// \brief Runs robust matching of `points` (epoch, its own coordinates) onto `reference`.
/// \param[in] point_indices the caller's index of each point (reported per observation); empty:
///            0..n−1. Non-finite points are skipped.
/// \param[in] guess EPOCH → REFERENCE start (4×4, cloud coordinates)
RobustMatchingReport
robustMatching(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& point_indices,
               const TargetSurface& reference, const ConjugateRule& rule,
               const RobustMatchingSettings& settings, const Eigen::Matrix4d& guess);

}  // namespace pcl_ls3d
