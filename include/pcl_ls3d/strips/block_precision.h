#pragma once
/// \file block_precision.h
/// \brief Honest σ per strip parameter: the spatial sandwich covariance of the pair engine
///        (spatial_precision.h) for a block. Observations within a few point spacings share
///        target points and are correlated; C = Q M Q with the middle term M estimated from the
///        observations' scores p v aᵀ summed over 3-D cells, averaged over the 8 grids of
///        2 × 2 × 2-cell blocks, each block's score corrected for its own leverage (CR3). In a
///        block a cell holds observations of several overlaps: its score has the blocks of every
///        strip they involve, and the correction uses the Qxx blocks of those strips only.

#include <pcl_ls3d/strips/overlap_contribution.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_ls3d {
namespace strips {

/// The sandwich's middle term M (7N × 7N) from the final pass's precision cells, the last
/// solve's Qxx (zero rows for parameters not estimated: their scores are corrected for the
/// estimated ones' leverage only, as a score test of held-out parameters needs), σ0 and the
/// a-priori weights (σ0² p_e for soft constraints on determinable parameters). With `step`
/// (7N), the scores are those of the residuals v + a·step (a freed model's one-step).
Eigen::MatrixXd
blockMiddleTerm(const std::vector<OverlapContribution>& contributions, const Eigen::MatrixXd& qxx,
                double sigma0, const Eigen::VectorXd& apriori_weights, const std::vector<bool>& determinable,
                const Eigen::VectorXd* step = nullptr);

/// The 7N × 7N covariance from the final pass's precision cells (contributions of all used
/// overlaps), the last solve's Qxx, σ0 and a-priori weights (soft constraints on determinable
/// parameters add σ0² p_e to M, as in the pair engine).
Eigen::MatrixXd
blockSandwichCovariance(const std::vector<OverlapContribution>& contributions, const Eigen::MatrixXd& qxx,
                        double sigma0, const Eigen::VectorXd& apriori_weights,
                        const std::vector<bool>& determinable);

}  // namespace strips
}  // namespace pcl_ls3d
