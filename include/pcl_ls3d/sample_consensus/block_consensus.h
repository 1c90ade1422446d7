#pragma once
/// \file block_consensus.h
/// \brief A high-breakdown start that uses what Li et al. say of deformation, that it lies "in a
///        continuous and gathering area" (beyond the paper): the matched observations are
///        grouped into square blocks of the surface (about 6 × 6 point spacings), and the
///        estimate is the one that the most observations in *consistent* blocks agree with — a
///        block is consistent when its mean squared residual is within the 99 % quantile of
///        χ²_k / k times σ_d², σ_d the neighbour-difference noise (neighbour_noise.h).
///
/// Why blocks: a point-wise criterion (LMS, LTS) may pick single points from the tails of the
/// stable and the moved part, and at 36 % deformed by 3.5 σ its optimum is a fit tilted between
/// them. A block cannot be split: a block inside the patch has a mean square of (1 + c²) σ², a
/// stable block on the far side of a tilted fit one of (1 + t²) σ², and the fit that leaves both
/// consistent is the stable part's own. Like RANSAC on blocks: random seeds of a few blocks,
/// each fit concentrated (refit on its consistent blocks until they repeat), the largest
/// consistent share wins (ties: the smaller sum of squares). PCL-free.

#include <pcl_ls3d/sample_consensus/linearized_matching.h>

#include <cstdint>

namespace pcl_ls3d {

/// \brief Settings of blockConsensus().
struct BlockConsensusSettings
{
  double block_spacings = 6.0;      ///< block edge in point spacings (≈ 36 points on a grid)
  std::size_t min_block_points = 8; ///< smaller blocks (the surface's edge) take no part
  int trials = 300;                 ///< random seeds
  int seed_blocks = 4;              ///< blocks per seed fit
  int max_steps = 30;               ///< concentration steps per seed
  /// Consistent: mean square < σ_d² (1 + z √(2 / k)), the normal approximation of χ²_k / k;
  /// z = 2.33 is its 99 % quantile.
  double quantile_z = 2.33;
  std::uint32_t seed = 1;
};

/// \brief What blockConsensus() found.
struct BlockConsensusResult
{
  bool ok = false;
  Vector7d parameters = identityParameters();  ///< reduced frame of the LinearizedMatching
  double support = 0.0;          ///< share of the observations in consistent blocks
  std::size_t blocks = 0;        ///< blocks with at least min_block_points observations
  std::size_t consistent = 0;    ///< of which consistent with the estimate
};

/// \param[in] lin the matched observations (linearised; only fit() and residuals() are used)
/// \param[in] noise σ_d of the residuals (> 0)
/// \param[in] start an estimate that competes as one more seed (e.g. the LTS fit)
BlockConsensusResult
blockConsensus(const LinearizedMatching& lin, double noise, const Vector7d& start,
               const BlockConsensusSettings& settings = BlockConsensusSettings());

}  // namespace pcl_ls3d
