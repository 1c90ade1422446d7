#pragma once
/// \file descriptive.h
/// \brief Robust descriptive statistics on a 1-D sample in double: median, MAD, quantiles.
///        PCL-free. Undefined results (empty input) are quiet NaN, never an exception.

#include <vector>

namespace pcl_ls3d {
namespace stats {

/// Scale that makes the MAD a consistent estimator of σ for normal data: 1 / Φ⁻¹(3/4).
constexpr double kMadToSigma = 1.4826;

/// \brief Median (mean of the two middle values for an even count); NaN when empty.
double
median(std::vector<double> values);

/// \brief The high median: the order statistic x_(⌊n/2⌋) counted from 0 (Python's
///        statistics.median_high), always one of the values and found in O(n) without averaging.
///        The engine's robust scales use it; NaN when empty.
double
medianHigh(std::vector<double> values);

/// \brief Median absolute deviation from the median, median |x_i − med(x)|.
/// \param[in] scaled multiply by kMadToSigma (1.4826) to estimate σ of normal data
/// \return NaN when empty; 0 for a single value or all-equal values
double
mad(const std::vector<double>& values, bool scaled = false);

/// \brief Quantile with linear interpolation between order statistics (Hyndman–Fan type 7,
///        the default of R and NumPy): q(p) = x_(h) + (h − ⌊h⌋)(x_(h+1) − x_(h)), h = (n − 1) p.
/// \param[in] p probability, clamped to [0, 1]
/// \return NaN when empty or p is NaN
double
quantile(std::vector<double> values, double p);

/// \brief Several quantiles of one sample, sorting once. Same rules as quantile().
std::vector<double>
quantiles(std::vector<double> values, const std::vector<double>& probs);

/// \brief Arithmetic mean; NaN when empty.
double
mean(const std::vector<double>& values);

/// \brief Sample standard deviation with n − 1 in the denominator; NaN when fewer than 2 values.
double
standardDeviation(const std::vector<double>& values);

}  // namespace stats
}  // namespace pcl_ls3d
