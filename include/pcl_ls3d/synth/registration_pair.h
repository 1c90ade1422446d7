#pragma once
/// \file registration_pair.h
/// \brief A source/target pair for surface matching with a known 7-parameter truth.
///
/// Frames (everything in metres):
///  - The TRUE surface (Terrain + buildings) lives in the TARGET frame ("world").
///  - Target points: uniform random (x, y) in the target footprint, z = true surface,
///    plus isotropic N(0, noise_sigma) noise on x, y and z.
///  - Source points: independent uniform random (x, y) in the source footprint, z = true surface,
///    plus noise (in the world frame), then mapped by truth.inverse(). Hence
///    truth.apply(source point) is exactly the noisy sample of the true surface, and
///    transforming the source by `truth` lands on the target surface within the noise.
///  - The source footprint (world frame) is [−size_x/2, size_x/2] × [−size_y/2, size_y/2]; the
///    target footprint is the same rectangle shifted by (1 − overlap)·size_x along +x, so
///    `overlap` is the fraction of the source footprint covered by the target.
///  - Clouds hold LOCAL coordinates (float, near 0). `origin` is the georeference offset: written
///    (global) coordinates = local + origin, the same origin for both clouds. `truth` is in local
///    coordinates, i.e. its rotation centre is the global point `origin`;
///    localToGlobal(truth.matrix(), origin, origin) is the truth in written coordinates.
///
/// Attributes: classification 2 (ground) or 6 (roof), point_source_id 1 (source) / 2 (target),
/// return 1 of 1, gps_time increasing with the index, intensity by class.

#include <pcl_ls3d/common/similarity_transform.h>
#include <pcl_ls3d/point_types.h>
#include <pcl_ls3d/synth/buildings.h>

#include <pcl/point_cloud.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <memory>
#include <string>

namespace pcl_ls3d {
namespace synth {

/// Default truth of a pair: t = (0.5, −0.3, 0.2) m, φ = 2e-3, ω = −1.5e-3, κ = 3e-3 rad,
/// m = 1 + 2e-4.
SimilarityTransform
defaultPairTruth();

/// \brief Settings of makeRegistrationPair().
struct RegistrationPairSettings
{
  std::uint32_t seed = 1;
  double size_x = 300.0, size_y = 300.0;  ///< source (and target) footprint extent [m]
  double source_density = 1.0;            ///< points per m²
  double target_density = 4.0;            ///< points per m²
  double overlap = 0.7;                   ///< fraction of the source footprint covered by the target, (0, 1]
  double noise_sigma = 0.05;              ///< isotropic noise per axis [m]
  bool buildings = true;                  ///< flat and gable roofed buildings (no trees)
  double relief = 10.0;                   ///< Terrain relief [m]
  double wavelength = 60.0;               ///< Terrain wavelength [m]
  BuildingSettings building_settings;     ///< density and sizes of the buildings
  SimilarityTransform truth = defaultPairTruth();    ///< maps SOURCE into TARGET's frame (local)
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< georeference offset of both clouds

  /// False (with a reason) for impossible values.
  bool
  isValid(std::string* why = nullptr) const;
};

/// \brief The generated pair and its truth.
struct RegistrationPair
{
  pcl::PointCloud<PointLiDAR>::Ptr source;           ///< local coordinates, source frame
  pcl::PointCloud<PointLiDAR>::Ptr target;           ///< local coordinates, target (= true surface) frame
  SimilarityTransform truth;                         ///< source → target, local coordinates
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< global = local + origin
  Eigen::AlignedBox2d source_footprint;              ///< in the target frame
  Eigen::AlignedBox2d target_footprint;              ///< in the target frame
  std::shared_ptr<const SurfaceModel> surface;       ///< the true surface (target frame)

  /// Truth as a 4×4 matrix in written (global) coordinates.
  Eigen::Matrix4d
  globalTruthMatrix() const;
};

/// \brief Generates a pair. Deterministic in settings.seed (independent of thread count).
///        Invalid settings: PCL_ERROR and empty (non-null) clouds.
RegistrationPair
makeRegistrationPair(const RegistrationPairSettings& settings);

}  // namespace synth
}  // namespace pcl_ls3d
