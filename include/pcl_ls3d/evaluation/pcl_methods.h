#pragma once
/// \file pcl_methods.h
/// \brief Runs PCL's own registration methods, the yardstick LS3D is compared with, on one input
///        with stated settings, each timed with pcl::StopWatch.
///
/// PCL 1.13 facts the settings below account for:
///  - ICP/ICP-N: transformation_epsilon is a SQUARED translation step; the rotation test is on the
///    cosine of the step angle computed in float, so it cannot resolve steps below ~2.4e-4 rad and
///    the translation test decides. hasConverged() is also true when the iteration limit is hit.
///  - GICP: converged when every element of the step matrix changes less than its epsilon
///    (rotation block: gicp_rotation_epsilon ≈ rad, translation: gicp_translation_epsilon, m);
///    the limit also counts as "converged".
///  - NDT: transformation_epsilon is the squared translation of the step; More–Thuente line search
///    with maximum step ndt_step_size; voxel edge ndt_resolution.
///  - Every method is a fresh object per run, so iteration counters start at 0.

#include <pcl_ls3d/evaluation/registration_run.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// \brief PCL's registration classes compared against LS3D.
enum class PclMethod
{
  ICP,          ///< pcl::IterativeClosestPoint (point-to-point, SVD)
  ICP_NORMALS,  ///< pcl::IterativeClosestPointWithNormals (point-to-plane, linear LS)
  GICP,         ///< pcl::GeneralizedIterativeClosestPoint (plane-to-plane)
  NDT,          ///< pcl::NormalDistributionsTransform
  /// pcl::IterativeClosestPoint with pcl::registration::TransformationEstimationSVDScale (Umeyama
  /// with scale): PCL's similarity-capable ICP, the fair row against LS3D with 7 parameters.
  ICP_SCALE
};

/// "PCL-ICP", "PCL-ICP-N", "PCL-GICP", "PCL-NDT", "PCL-ICP-S".
std::string
pclMethodName(PclMethod method);

/// The four rigid methods, in table order (ICP_SCALE is asked for explicitly).
const std::vector<PclMethod>&
allPclMethods();

/// \brief Settings of the PCL methods. Defaults are chosen for airborne-like data in metres with
///        initial misalignments below ~1 m, and use LS3D's stopping thresholds where PCL has an
///        equivalent (1e-5 m translation step, 1e-6 rad rotation step).
struct PclMethodSettings
{
  double max_correspondence_distance = 2.0;  ///< [m] ICP, ICP-N, GICP
  int max_iterations = 50;                   ///< all methods
  double transformation_epsilon = 1e-10;     ///< [m²] ICP, ICP-N, NDT: squared translation step
  double rotation_epsilon = 1.0 - 5e-13;     ///< cos(step angle) for ICP, ICP-N (≈1e-6 rad)
  double gicp_translation_epsilon = 1e-5;    ///< [m] GICP: per-element translation step
  double gicp_rotation_epsilon = 1e-6;       ///< [rad] GICP: per-element rotation-matrix step
  int gicp_k_correspondences = 20;           ///< GICP: neighbours per covariance (PCL default)
  /// GICP: inner BFGS stops when the (per-point mean) translation and rotation gradient norms fall
  /// below this (PCL default; 1e-4 and 1e-6 gave identical results on a 150 m synthetic pair).
  double gicp_gradient_tolerance = 1e-2;
  int normal_k = 15;                ///< ICP-N: neighbours per target normal
  double ndt_resolution = 2.0;      ///< [m] NDT voxel edge
  double ndt_step_size = 0.5;       ///< [m] NDT maximum line-search step
  double ndt_outlier_ratio = 0.55;  ///< NDT (PCL default)
  unsigned int threads = 0;         ///< NormalEstimationOMP threads (0 = all cores)

  /// One line listing every value, for tables and docs; lengths labelled `unit` (the data's).
  std::string
  describe(const std::string& unit = "m") const;

  /// The same settings for data in another length unit: every length (correspondence distance,
  /// translation steps, NDT resolution and step) divided by \a metres_per_unit, the squared step
  /// by its square (data in feet: inUnit(0.3048)).
  PclMethodSettings
  inUnit(double metres_per_unit) const;
};

/// \brief Runs one PCL method from the identity guess. Never throws; on failure run.ran is false
///        and run.message says why. The returned run has no rms/error yet (see RunEvaluation).
RegistrationRun
runPclMethod(PclMethod method, const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& source,
             const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& target, const PclMethodSettings& settings = {});

}  // namespace evaluation
}  // namespace pcl_ls3d
