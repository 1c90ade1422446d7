#pragma once
/// \file subset_search.h
/// \brief High-breakdown searches over random p-subsets of a LinearizedMatching: least median of
///        squares (Li et al. 2001, eqs. 11–12; Rousseeuw & Leroy 1987) and least trimmed squares
///        with concentration steps (FAST-LTS, Rousseeuw & Van Driessen 2006). Parallel over
///        subsets (OpenMP); the result does not depend on the number of threads (subset k draws
///        from its own random stream and ties go to the lower k).
///
/// Cost per subset: one Gauss–Markoff solve over p rows and the linearised residuals of the
/// scored observations (7 multiply-adds each). Two shortcuts, both exact for the criterion on
/// the scored set:
///  - early exit (LMS): scoring stops once more than half of the residuals exceed the best
///    median so far — that subset cannot win;
///  - a scoring subsample: with more than `score_points` observations the subsets are ranked
///    on a fixed random subsample of that size, and the best `finalists` are re-scored on all.

#include <pcl_ls3d/sample_consensus/linearized_matching.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_ls3d {

/// \brief Li et al. 2001, eq. 12: the number of subsets m such that at least one of them is free
///        of contamination with probability P: m = ln(1 − P) / ln(1 − (1 − ε)^p).
///        ε = 0.5, p = 7, P = 0.99 gives 588 (the paper's 600 for 99.1 %).
int
subsetsForConfidence(double contamination, double confidence, int sample_size);

/// \brief The default m: eq. 12 with P = 0.999, but at least 600 (the paper's tests) and at
///        least 3000 when ε > 0.4 (Li et al.: "600 sub-samples are not enough" above 40 %, the
///        clean part's geometry gets poor).
int
defaultSubsets(double contamination, int sample_size);

/// \brief Settings of both searches.
struct SubsetSearchSettings
{
  int subsets = 3000;                ///< random p-subsets drawn (LTS: starts)
  int sample_size = 7;               ///< p (Li: 7 points for 6 parameters)
  std::uint32_t seed = 1;            ///< subset k uses stream (seed, k)
  std::size_t score_points = 20000;  ///< rank subsets on a random subsample of this many (0: all)
  int finalists = 10;                ///< candidates re-scored on all observations (and LTS C-stepped)
  bool early_exit = true;            ///< LMS: stop scoring a subset that cannot win
  /// LTS coverage: h = max(⌊(m + p + 1)/2⌋, ⌈α m⌉); α = 0.5 gives the 50 % breakdown point.
  double coverage = 0.5;
  int start_csteps = 2;  ///< LTS: C-steps on every start (FAST-LTS: 2)
  int max_csteps = 50;   ///< LTS: C-steps on a finalist until the subset repeats
};

/// \brief What a search found.
struct SubsetSearchResult
{
  bool ok = false;
  Vector7d parameters = identityParameters();  ///< best estimate (reduced frame)
  double criterion = 0.0;  ///< LMS: med v² over all observations; LTS: Σ of the h smallest v² / h
  double scale = 0.0;  ///< LMS: 1.4826 (1 + 5/(m − p)) √med v²; LTS: consistency-corrected √criterion
  int drawn = 0;       ///< subsets drawn
  int valid = 0;       ///< of which could be fitted (determinable, finite)
  int best_subset = -1;      ///< index k of the winning subset
  std::size_t scored = 0;    ///< observations each subset was ranked on
  std::size_t coverage = 0;  ///< LTS: h
  int csteps = 0;            ///< LTS: C-steps of the winner
  std::vector<int> sample;   ///< observations of the winning subset (LMS) / start (LTS)
};

/// med v² of all observations at X (the LMS criterion).
double
lmsCriterion(const LinearizedMatching& lin, const Vector7d& X);
/// Σ of the h smallest v² / h at X with h from `coverage` (the LTS criterion).
double
ltsCriterion(const LinearizedMatching& lin, const Vector7d& X, double coverage);

/// Least median of squares: the subset estimate minimising med_j v_j² (eq. 11).
SubsetSearchResult
leastMedianOfSquares(const LinearizedMatching& lin, const SubsetSearchSettings& settings);

/// FAST-LTS: min Σ_{j ≤ h} v²_(j) over starts from p-subsets, each concentrated by C-steps
/// (fit the h observations of smallest |v|, repeat), the best finalists iterated to convergence.
SubsetSearchResult
leastTrimmedSquares(const LinearizedMatching& lin, const SubsetSearchSettings& settings);

}  // namespace pcl_ls3d
