#pragma once
/// \file transform_error.h
/// \brief How far an estimated transform is from the truth, judged by what it does to the data:
///        the displacement |T_est x − T_true x| it causes over the source points and over the
///        corners of the source bounding box, and the error of each of the 7 parameters.
///        PCL-free, double precision.
///
/// Both transforms map source coordinates into target coordinates and must be expressed in the
/// same frame (e.g. both in the clouds' common local frame). Displacement errors do not depend on
/// that frame; translation (and hence parameter) errors do, because a rotation error moves the
/// translation by the lever arm to the frame's origin: report the frame next to them.

#include <pcl_ls3d/common/similarity_transform.h>

#include <Eigen/Core>

#include <cstddef>

namespace pcl_ls3d {
namespace evaluation {

/// \brief Displacement and parameter errors of one estimated transform.
struct TransformError
{
  std::size_t points = 0;  ///< source points evaluated
  double mean = 0.0;       ///< mean |T_est x − T_true x| over the points [length]
  double rms = 0.0;        ///< root mean square of the same [length]
  double max = 0.0;        ///< maximum over the points [length]
  /// Maximum over the 8 corners of the points' axis-aligned bounding box [length]. Because the
  /// displacement (T_est − T_true) x is affine in x, this bounds the error anywhere in the box.
  double max_bbox = 0.0;
  /// Estimated minus true parameter (tx, ty, tz, φ, ω, κ, m), angles wrapped to (−π, π]; both
  /// decomposed with SimilarityTransform::fromMatrix.
  Vector7d parameters = Vector7d::Zero();
  bool valid = false;  ///< false: no points or non-finite input
};

/// Displacement of one point, |T_est x − T_true x| (homogeneous 4×4 matrices).
double
displacementError(const Eigen::Matrix4d& T_est, const Eigen::Matrix4d& T_true, const Eigen::Vector3d& x);

/// Estimated minus true parameters (tx, ty, tz, φ, ω, κ, m); angle differences wrapped to
/// (−π, π].
Vector7d
parameterErrors(const Eigen::Matrix4d& T_est, const Eigen::Matrix4d& T_true);

/// All errors over the source points (one column per point). Returns valid == false when the
/// point set is empty or a transform is not finite; non-finite points are skipped.
TransformError
computeTransformError(const Eigen::Matrix4d& T_est, const Eigen::Matrix4d& T_true,
                      const Eigen::Matrix3Xd& source_points);

}  // namespace evaluation
}  // namespace pcl_ls3d
