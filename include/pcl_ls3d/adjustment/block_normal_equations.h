#pragma once
/// \file block_normal_equations.h
/// \brief Normal equations of a block adjustment of B parameter blocks (7 parameters each, one
///        per strip): N is block-sparse, with a 7×7 block N_ij for every pair of blocks linked
///        by observations. Each overlap contributes the 14×14 normal equations of its rows
///        [a_i | a_j] (pair_matcher.h); summing them is all a block adjustment needs, and all a
///        remote worker has to send back for its overlap.

#include <pcl_ls3d/adjustment/gauss_markov.h>
#include <pcl_ls3d/adjustment/normal_equations.h>

#include <Eigen/SparseCore>

#include <map>
#include <utility>

namespace pcl_ls3d {

/// \brief Σ over overlaps of their 14×14 contributions, stored as 7×7 blocks (upper triangle).
class BlockNormalEquations
{
public:
  explicit BlockNormalEquations(int blocks = 0);

  int
  blocks() const
  {
    return blocks_;
  }
  /// 7 × blocks().
  Eigen::Index
  unknowns() const
  {
    return 7 * static_cast<Eigen::Index>(blocks_);
  }

  /// Adds the contribution of observations with rows [a_i | a_j] (i ≠ j).
  void
  addOverlap(int i, int j, const PairNormalEquations& contribution);
  /// Adds observations of block i alone (rows a_i).
  void
  addBlock(int i, const NormalEquations& contribution);
  /// Sums another system with the same number of blocks.
  BlockNormalEquations&
  operator+=(const BlockNormalEquations& other);

  /// The full symmetric N as a sparse matrix.
  Eigen::SparseMatrix<double>
  sparseMatrix() const;
  /// The full symmetric N, dense.
  Eigen::MatrixXd
  denseMatrix() const;
  /// b = AᵀPL.
  const Eigen::VectorXd&
  rhs() const
  {
    return b_;
  }
  double
  ltpl() const
  {
    return ltpl_;
  }
  /// Observations with p > 0.
  std::size_t
  observations() const
  {
    return n_;
  }
  /// Number of non-zero 7×7 blocks in the upper triangle (diagonal included).
  std::size_t
  nonZeroBlocks() const
  {
    return upper_.size();
  }

private:
  void
  addToBlock(int i, int j, const Matrix7d& value);

  int blocks_ = 0;
  std::map<std::pair<int, int>, Matrix7d> upper_;  ///< (i ≤ j) → N_ij
  Eigen::VectorXd b_;
  double ltpl_ = 0.0;
  std::size_t n_ = 0;
};

/// \brief Solves a block system with a-priori observations (problem vectors of length
///        7 × blocks). Up to `dense_limit` unknowns the dense solve of gauss_markov.h (eigenvalue
///        rank test); beyond, a sparse LDLᵀ with a pivot rank test: a parameter whose scaled pivot
///        is below threshold × its own diagonal (its column almost entirely explained by the
///        others) is undeterminable, removed, and the system refactored. Qxx is returned dense.
GaussMarkovSolution
solveGaussMarkov(const BlockNormalEquations& ne, const GaussMarkovProblem& problem,
                 Eigen::Index dense_limit = 700);

}  // namespace pcl_ls3d
