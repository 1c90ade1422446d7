#pragma once
/// \file similarity_transform.h
/// \brief The 7-parameter similarity x' = t + m R(φ, ω, κ) x (Zuo et al. 2012, eq. 2), the one
///        parameterisation shared by the adjustment, the generators and the reports.
///
/// Rotation convention (photogrammetric φ-ω-κ, Y primary axis):
///   R(φ, ω, κ) = R_Y(φ) · R_X(ω) · R_Z(κ), all right-handed, angles in radians.
/// Parameter order everywhere (vectors, Qxx, reports): tx, ty, tz, φ, ω, κ, m.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <string>

namespace pcl_ls3d {

using Vector7d = Eigen::Matrix<double, 7, 1>;
using Matrix7d = Eigen::Matrix<double, 7, 7>;

/// Index of each parameter in Vector7d / Matrix7d.
enum SimilarityParameter : int
{
  TX = 0,
  TY = 1,
  TZ = 2,
  PHI = 3,
  OMEGA = 4,
  KAPPA = 5,
  SCALE = 6
};

/// Names in parameter order: "tx", "ty", "tz", "phi", "omega", "kappa", "m".
const std::array<std::string, 7>&
similarityParameterNames();

/// \brief Seven parameters of a similarity transform, in double.
struct SimilarityTransform
{
  Eigen::Vector3d t = Eigen::Vector3d::Zero();  ///< translation [length unit of the data]
  double phi = 0.0;                             ///< rotation about Y [rad]
  double omega = 0.0;                           ///< rotation about X [rad]
  double kappa = 0.0;                           ///< rotation about Z [rad]
  double m = 1.0;                               ///< scale [-]

  SimilarityTransform() = default;
  /// From (tx, ty, tz, φ, ω, κ, m).
  explicit SimilarityTransform(const Vector7d& p);

  Vector7d
  vector() const;

  /// R(φ, ω, κ) = R_Y(φ) R_X(ω) R_Z(κ).
  Eigen::Matrix3d
  rotation() const;

  /// 4×4 homogeneous matrix [m R | t].
  Eigen::Matrix4d
  matrix() const;

  /// x' = t + m R x.
  Eigen::Vector3d
  apply(const Eigen::Vector3d& x) const;

  /// The inverse similarity (x = R^T (x' - t) / m).
  SimilarityTransform
  inverse() const;

  /// Decomposes a 4×4 similarity matrix (scale = cube root of det of the 3×3 block; the
  /// rotation is the closest orthonormal matrix). Angles come back in (-π, π], ω in [-π/2, π/2].
  static SimilarityTransform
  fromMatrix(const Eigen::Matrix4d& T);
};

/// \brief Re-expresses a transform given in local coordinates (x_local = x_global - origin) in
///        global coordinates: T_global = Shift(origin_target) · T_local · Shift(-origin_source).
Eigen::Matrix4d
localToGlobal(const Eigen::Matrix4d& T_local, const Eigen::Vector3d& origin_source,
              const Eigen::Vector3d& origin_target);

/// Inverse of localToGlobal.
Eigen::Matrix4d
globalToLocal(const Eigen::Matrix4d& T_global, const Eigen::Vector3d& origin_source,
              const Eigen::Vector3d& origin_target);

}  // namespace pcl_ls3d
