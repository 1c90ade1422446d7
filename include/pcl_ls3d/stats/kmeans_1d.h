#pragma once
/// \file kmeans_1d.h
/// \brief Deterministic 1-D k-means (Lloyd) with quantile seeding. IMRG (Wang et al. 2021
///        §3.2.2) clusters the segment plane-fit residuals R_i into 3 groups and takes the
///        smallest gap between the centres as the similarity threshold s_t. PCL-free, double.

#include <cstddef>
#include <vector>

namespace pcl_ls3d {
namespace stats {

/// \brief Result of kMeans1D().
struct KMeans1DResult
{
  bool valid = false;              ///< false for empty input or k == 0
  std::vector<double> centres;     ///< ascending; fewer than k if the sample has fewer distinct values
  std::vector<std::size_t> sizes;  ///< number of values per centre
  std::vector<int> assignments;    ///< per input value: index into `centres`; −1 for NaN/inf input
  double smallest_gap = 0.0;       ///< min centres[c+1] − centres[c]; NaN with fewer than 2 centres
  double within_ss = 0.0;          ///< Σ (x − centre)² over assigned values
  std::size_t iterations = 0;      ///< Lloyd iterations run
  bool converged = false;          ///< assignments stopped changing before max_iterations
};

/// \brief 1-D k-means. Seeds are the (c + ½)/k quantiles of the finite values (so the same
///        input always gives the same answer). If there are at most k distinct values, each
///        distinct value is its own centre (the exact optimum). Empty clusters get the value
///        farthest from its centre. Non-finite values are ignored (assignment −1).
KMeans1DResult
kMeans1D(const std::vector<double>& values, std::size_t k, std::size_t max_iterations = 100);

}  // namespace stats
}  // namespace pcl_ls3d
