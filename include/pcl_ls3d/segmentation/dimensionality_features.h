#pragma once
/// \file dimensionality_features.h
/// \brief Per-point geometric features of IMRG (Wang et al. 2021 §2, after Weinmann et al. 2015):
///        optimal neighbourhood size by minimal eigen-entropy, dimensionality a1D/a2D/a3D, normal,
///        principal direction and plane-fitting residual. PCL-free core, double arithmetic.

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {

/// \brief Dimensionality class of a point: argmax of (a1D, a2D, a3D).
enum class Dimensionality : std::uint8_t
{
  Linear = 0,      ///< a1D largest: poles, wires, edges
  Planar = 1,      ///< a2D largest: ground, roofs, facades
  Volumetric = 2,  ///< a3D largest: vegetation, clutter
  Invalid = 255    ///< not processed (non-finite coordinates or outside the indices)
};

/// \brief Features of one point, computed from its optimal neighbourhood.
///
/// With λ1 ≥ λ2 ≥ λ3 the eigenvalues of the neighbourhood covariance
/// C = (1/k) Σ (p − μ)(p − μ)ᵀ:
///   a1D = (√λ1 − √λ2)/√λ1,  a2D = (√λ2 − √λ3)/√λ1,  a3D = √λ3/√λ1  (they sum to 1).
/// The eigen-entropy minimised over k is E = −Σ e_i ln e_i with e_i = λ_i / Σλ.
struct PointFeatures
{
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();     ///< eigenvector of λ3, z ≥ 0
  Eigen::Vector3f principal = Eigen::Vector3f::UnitX();  ///< eigenvector of λ1
  float a1d = 0.f, a2d = 0.f, a3d = 0.f;                 ///< dimensionality features
  float residual = 0.f;  ///< RMS distance [m] of the neighbourhood to its LS plane, √λ3
  float entropy = 0.f;   ///< eigen-entropy at the chosen k
  std::uint16_t k = 0;   ///< optimal neighbourhood size (neighbours incl. the point itself)
  Dimensionality dimensionality = Dimensionality::Invalid;
};

/// \brief Range of neighbourhood sizes scanned for the minimal eigen-entropy.
struct NeighbourhoodSettings
{
  int k_min = 10;   ///< smallest k tested (≥ 3)
  int k_max = 100;  ///< largest k tested; k_min == k_max is the fixed-k mode
  int k_step = 10;  ///< increment between tested k
};

/// \brief Features of one point from its neighbours sorted by increasing distance (the point
///        itself first). Scans k = k_min, k_min + step, ..., ≤ min(k_max, n) with running
///        prefix moments (one pass over the neighbours, no re-sorting) and keeps the k of
///        minimal eigen-entropy. A neighbourhood of zero extent (all duplicates) gives
///        dimensionality Volumetric with a3D = 1, residual 0 and the default normal: it has no
///        preferred direction, so it must not join linear or planar growth.
/// \param[in] sorted_neighbours coordinates, nearest first; size ≥ 3 (fewer gives Invalid)
/// \param[in] settings k range
///        Moments are accumulated in double relative to the first neighbour.
PointFeatures
computePointFeatures(const std::vector<Eigen::Vector3f>& sorted_neighbours,
                     const NeighbourhoodSettings& settings);

}  // namespace segmentation
}  // namespace pcl_ls3d
