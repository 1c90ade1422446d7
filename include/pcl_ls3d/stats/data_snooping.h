#pragma once
/// \file data_snooping.h
/// \brief Baarda's data snooping: the w-test on normalised residuals, with iterative backward
///        elimination of gross errors (one observation per round, then re-estimate).
///
/// Two uses in pcl_ls3d:
///  - a 1-D sample (IMRG, Wang et al. 2021 §3.2.2): the merging distances D and volume changes ΔV
///    contain a few large "gross" values; they are removed one by one and the maximum of what
///    remains becomes the threshold d_t or V_t;
///  - adjustment residuals (LS3D robust estimation): w_i = v_i / (σ0 √(r_i / p_i)) with the
///    redundancy numbers r_i; the caller re-adjusts after each rejection.
/// PCL-free, double precision.

#include <cstddef>
#include <vector>

namespace pcl_ls3d {
namespace stats {

/// \brief Two-sided critical value k of the standard normal: P(|Z| > k) = alpha.
///        alpha = 0.001 gives 3.2905 (Baarda's α0 for a single w-test); 0.05 gives 1.9600.
/// \return NaN unless 0 < alpha < 1
double
normalCriticalValue(double alpha);

/// \brief Settings of the 1-D backward elimination.
struct DataSnoopingSettings
{
  double alpha = 0.001;         ///< significance α0 of each single w-test (two-sided)
  double critical_value = 0.0;  ///< if > 0, used instead of normalCriticalValue(alpha)
  /// σ of one value. If > 0 it is taken as known (Baarda's w-test proper); otherwise σ is
  /// re-estimated from the values kept so far (sample σ, n − 1), which is Pope's τ-style test.
  double sigma_apriori = 0.0;
  std::size_t min_kept = 3;  ///< never reduce the sample below this many values
  /// Only test values above the mean (IMRG: gross distances / volume changes are large ones).
  /// The critical value stays the two-sided k of alpha (so the one-sided test has level α/2).
  bool one_sided_upper = false;
};

/// \brief Result of dataSnooping(). Indices refer to the input vector, in ascending order.
struct DataSnoopingResult
{
  bool valid = false;                 ///< false for an empty input (scalars are then NaN)
  std::vector<std::size_t> kept;      ///< indices of accepted values
  std::vector<std::size_t> rejected;  ///< indices of values removed as gross errors
  double mean = 0.0;                  ///< mean of the kept values
  double sigma = 0.0;                 ///< σ used in the final test (a priori, or sample σ of kept)
  double max_kept = 0.0;              ///< maximum kept value (IMRG's d_t / V_t)
  double critical_value = 0.0;        ///< the k actually used
  double max_w = 0.0;                 ///< largest |w| among kept values in the final round
  std::size_t iterations = 0;         ///< number of rejection rounds
};

/// \brief Iterative backward elimination on a 1-D sample: w_i = |x_i − mean| / σ over the kept
///        values; while max w_i > k, remove that value and re-estimate mean and σ.
///        Stops when nothing exceeds k, when σ is 0 (all kept values equal), or at min_kept.
///        NaN / inf input values are rejected up front (listed in `rejected`).
///        With an estimated σ, |w| ≤ (n − 1)/√n, so fewer than ~14 values can never reject at
///        k = 3.29: the test has no power on tiny samples (stated, not hidden).
DataSnoopingResult
dataSnooping(const std::vector<double>& values, const DataSnoopingSettings& settings = {});

/// \brief One w-test round on adjustment residuals (the caller re-adjusts and calls again).
struct BaardaTestResult
{
  std::vector<double> w;     ///< w_i = v_i / (σ0 √(r_i / p_i)); 0 where r_i ≤ min_redundancy
  std::vector<bool> tested;  ///< false where r_i ≤ min_redundancy (uncontrolled observation)
  long worst = -1;           ///< index of the largest |w_i| above k, −1 if none
  double max_abs_w = 0.0;    ///< largest |w_i| among tested observations
};

/// \brief Baarda's w-test statistic for every residual (Baarda 1968: σ_vi = σ0 √(r_i/p_i)).
/// \param[in] v residuals v_i
/// \param[in] r redundancy numbers r_i = 1 − p_i a_iᵀ Qxx a_i, in [0, 1]
/// \param[in] p weights p_i (> 0); an empty vector means all 1
/// \param[in] sigma0 σ0 (a priori for the w-test proper)
/// \param[in] critical_value k, e.g. normalCriticalValue(0.001)
/// \param[in] min_redundancy observations with r_i at or below this are not tested
/// \return empty result (worst = −1, w empty) if sizes disagree or sigma0 ≤ 0
BaardaTestResult
baardaTest(const std::vector<double>& v, const std::vector<double>& r, const std::vector<double>& p,
           double sigma0, double critical_value, double min_redundancy = 1e-6);

}  // namespace stats
}  // namespace pcl_ls3d
