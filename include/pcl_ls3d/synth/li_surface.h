#pragma once
/// \file li_surface.h
/// \brief The deformation-detection test surface of Li et al. (2001), section "Test Data Sets".
///
/// Reference surface S: a grid_size × grid_size grid (default 50 × 50) with spacing 100 units,
/// centred on the origin (x, y ∈ [−2450, 2450]); heights from a seeded Terrain rescaled so that
/// max − min over the grid equals `relief` (default 5000) and centred on z = 0. S is noise-free
/// unless noise_on_reference.
/// Mate surface S': the same nodes with heights h + e + d, e ~ N(0, σ) on every node and
/// d ~ N(c·σ, σ) on the deformed nodes only (the paper's N(c, σ) with c given in σ). The deformed
/// nodes are "gathered": the round(percent/100 · N) nodes nearest (Chebyshev distance in grid
/// steps, ties by Euclidean distance, then index) to one of nine anchors — a corner, the middle
/// of an edge, or the centre. "Upper" is +y, "right" is +x.
/// Finally S' is moved by truth.inverse(), so `truth` maps the mate onto the reference frame
/// (same convention as a RegistrationPair: mate = source, reference = target). Point i of both
/// clouds is grid node i (row-major, row = y index): truth.apply(mate[i]) − reference[i] =
/// (0, 0, e_i + d_i) up to float rounding.

#include <pcl_ls3d/common/similarity_transform.h>
#include <pcl_ls3d/point_types.h>

#include <pcl/point_cloud.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace synth {

/// The nine deformation positions of Li et al. (2001).
enum class DeformationPosition : int
{
  UPPER_LEFT = 0,
  UPPER,
  UPPER_RIGHT,
  LEFT,
  MIDDLE,
  RIGHT,
  LOWER_LEFT,
  LOWER,
  LOWER_RIGHT
};

/// "upper_left", "upper", ..., "lower_right".
const char*
toString(DeformationPosition p);

/// Parses the names of toString(); false if unknown.
bool
parseDeformationPosition(const std::string& name, DeformationPosition& p);

/// Default rigid truth of the Li surface, that of Li et al.'s Table 4: t = (500, 500, 500) units,
/// φ = ω = κ = 5°, m = 1. LHD (LZD, 6 parameters) converges to it from the identity.
SimilarityTransform
defaultLiTruth();

/// \brief Settings of makeLiSurface(); defaults reproduce the paper's Table 2 case.
struct LiSurfaceSettings
{
  std::uint32_t seed = 1;
  int grid_size = 50;      ///< nodes per side
  double spacing = 100.0;  ///< grid interval [units]
  double relief = 5000.0;  ///< max − min height of S [units]
  /// Terrain wavelength [units]. At 3000 a local quadric of 20 grid nodes interpolates the
  /// reference to well below σ (LHD residual scale 19.9 for σ = 20 without deformation); at
  /// 1500 its misfit adds about 22 units RMS, more than the noise itself.
  double wavelength = 3000.0;
  double noise_sigma = 20.0;         ///< σ of the random errors N(0, σ)
  double deformation_percent = 9.0;  ///< share of deformed nodes [%], 0–100
  double deformation_c = 10.0;       ///< deformation mean in units of σ: d ~ N(c·σ, σ)
  DeformationPosition position = DeformationPosition::UPPER_RIGHT;
  bool noise_on_reference = false;               ///< also add N(0, σ) to S
  SimilarityTransform truth = defaultLiTruth();  ///< maps the mate onto the reference (m = 1: rigid)

  bool
  isValid(std::string* why = nullptr) const;
};

/// \brief Reference and mate surfaces with their truth.
struct LiSurface
{
  pcl::PointCloud<PointLiDAR>::Ptr reference;  ///< S (point_source_id 1)
  pcl::PointCloud<PointLiDAR>::Ptr mate;       ///< S', deformed, noisy, moved (point_source_id 2)
  SimilarityTransform truth;                   ///< mate → reference
  std::vector<std::uint8_t> deformed;          ///< per node: 1 inside the deformation
  std::vector<int> deformed_indices;           ///< the same as indices
  std::vector<double> height;                  ///< noise-free height of S per node
  std::vector<double> deformation;             ///< d_i added to the mate (0 outside)
  std::vector<double> mate_noise;              ///< e_i added to the mate
  double percent = 0.0;                        ///< achieved deformed share [%]
};

/// Generates the pair; invalid settings: PCL_ERROR and empty (non-null) clouds.
LiSurface
makeLiSurface(const LiSurfaceSettings& settings);

}  // namespace synth
}  // namespace pcl_ls3d
