#pragma once
/// \file block_trimmed_squares.h
/// \brief A high-breakdown start that uses what Li et al. say of deformation, that it lies "in a
///        continuous and gathering area" (beyond the paper): least trimmed squares over blocks
///        of the surface instead of points. The matched observations are grouped into square
///        blocks (about 6 × 6 point spacings on the dominant plane); the estimate minimises the
///        mean of the h smallest block mean squares (h = 40 % of the blocks), found FAST-LTS
///        style: random seeds of a few blocks, each concentrated (refit on its h best blocks
///        while the criterion falls).
///
/// Why blocks: a point-wise criterion (LMS, LTS) picks single points from the tails of the
/// stable and the moved part, and at 36 % deformed by 3.5 σ its optimum is a fit tilted between
/// them. A block cannot be split: a block inside the patch has a mean square of (1 + c²) σ², a
/// stable block on the far side of a tilted fit one of (1 + t²) σ², and the trimmed blocks of
/// the stable part's own fit are ≈ σ². 40 %, not 50 %: blocks across the patch's rim are lost to
/// both parts, and at 46 % deformed fewer than half of the blocks are clean stable ones; a fit
/// to the patch can then compete, which the caller's choice between starts resolves
/// (deformation/start_choice.h: a fit must leave at least half of the surface outside its
/// deformed regions). Blocks with fewer than half the median block's observations (the
/// surface's edge) take no part: their mean squares are the noisiest. PCL-free.

#include <pcl_ls3d/sample_consensus/linearized_matching.h>

#include <cstdint>

namespace pcl_ls3d {

/// \brief Settings of blockTrimmedSquares().
struct BlockTrimmedSquaresSettings
{
  double block_spacings = 6.0;  ///< block edge in point spacings (≈ 36 points on a grid)
  double coverage = 0.4;        ///< share of the blocks the criterion keeps, in (0, 1] (else no estimate)
  int trials = 300;             ///< random seeds
  int seed_blocks = 4;          ///< blocks per seed fit
  int max_csteps = 30;          ///< concentration steps per seed
  std::uint32_t seed = 1;
};

/// \brief What blockTrimmedSquares() found.
struct BlockTrimmedSquaresResult
{
  bool ok = false;
  Vector7d parameters = identityParameters();  ///< reduced frame of the LinearizedMatching
  double scale = 0.0;      ///< √ of the criterion (√ of the mean of the kept blocks' mean squares)
  double support = 0.0;    ///< share of the observations in the kept blocks
  std::size_t blocks = 0;  ///< blocks taking part
  std::size_t kept = 0;    ///< h
};

/// \param[in] lin the matched observations (linearised; only fit() and residuals() are used)
/// \param[in] start an estimate that competes as one more seed (e.g. the LTS fit)
BlockTrimmedSquaresResult
blockTrimmedSquares(const LinearizedMatching& lin, const Vector7d& start,
                    const BlockTrimmedSquaresSettings& settings = BlockTrimmedSquaresSettings());

}  // namespace pcl_ls3d
