#pragma once
/// \file registration_run.h
/// \brief The one result row every registration method produces in pcl_ls3d_compare and the
///        benchmarks, and the method-independent quality figures computed for every row alike.

#include <pcl_ls3d/evaluation/transform_error.h>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// The transformation of a run without an estimate: its RMS and errors are "-" / null.
inline const Eigen::Matrix4d kNoTransformation =
    Eigen::Matrix4d::Constant(std::numeric_limits<double>::quiet_NaN());

/// \brief What one method did on one input (all clouds in their common local frame).
struct RegistrationRun
{
  std::string name;     ///< "PCL-ICP", "PCL-ICP-N", "PCL-GICP", "PCL-NDT", "LS3D-LND", ...
  bool ran = false;     ///< false: the method could not be set up or threw
  std::string message;  ///< why it failed / how it stopped
  int iterations = 0;   ///< iterations of this alignment (not accumulated)
  /// Wall time [s] from handing over the clouds to the end of align(): search structures,
  /// covariances, NDT grid and (PCL-ICP-N) normal estimation included.
  double time_s = 0.0;
  double normals_time_s = 0.0;  ///< part of time_s spent estimating normals (PCL-ICP-N)
  /// Process CPU time [s] over the same span, summed over all threads. On a loaded machine it
  /// shows the work done where the wall time only shows the share of the CPU that was granted.
  double cpu_s = 0.0;
  /// Stopped by its own convergence criterion before the iteration limit. PCL's hasConverged()
  /// is also true when ICP/GICP/NDT merely hit the limit; that value is kept in pcl_converged.
  bool converged = false;
  bool pcl_converged = false;  ///< the method's hasConverged()
  /// The method judged its own result (LS3D's quality gate: pcl_converged is false for a
  /// refused fit); PCL's methods have no such check and hasConverged() is not one.
  bool quality_checked = false;
  /// Stopped because it reached its iteration limit (PCL: nr_iterations_ == max; LS3D:
  /// MAX_ITERATIONS). A method that hit the limit did not converge by its own criterion.
  bool hit_limit = false;
  /// How it stopped, one word for tables: "conv", "LIMIT", "noconv" (PCL) or LS3D's termination
  /// ("CONVERGED", "MAX_ITERATIONS", "STALLED", "UNRELIABLE", "IMPLAUSIBLE_SCALE", ...).
  std::string stop;
  /// RMS of the nearest-neighbour distances source→target after alignment, over the source
  /// points whose neighbour is within RunEvaluation::rms_max_distance (same for every method).
  double rms = std::numeric_limits<double>::quiet_NaN();
  std::size_t rms_points = 0;                                ///< source points inside that distance
  double sigma0 = std::numeric_limits<double>::quiet_NaN();  ///< LS3D's σ̂0 (NaN for PCL)
  /// Source → target, local; all NaN (kNoTransformation) when the method gave no estimate.
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();
  TransformError error;  ///< against the truth, when one was given (error.valid)
};

/// \brief Shared, untimed evaluation of every run: the uniform RMS and the truth errors.
struct RunEvaluation
{
  using CloudXYZ = pcl::PointCloud<pcl::PointXYZ>;

  /// Builds the target kd-tree once and keeps the source points in double.
  RunEvaluation(const CloudXYZ::ConstPtr& source, const CloudXYZ::ConstPtr& target, double rms_max_distance);

  /// Fills run.rms, run.rms_points and, when truth is not null, run.error.
  void
  evaluate(RegistrationRun& run, const Eigen::Matrix4d* truth) const;

  double rms_max_distance;         ///< [length] neighbours farther than this are not counted
  Eigen::Matrix3Xd source_points;  ///< source (local frame), double
  pcl::KdTreeFLANN<pcl::PointXYZ> target_tree;
};

/// CPU time of this process so far [s], all threads (CLOCK_PROCESS_CPUTIME_ID).
double
processCpuSeconds();

/// \brief One method's run named `name`, the way every row of a comparison is run: refused on an
///        empty source or target, timed (wall and process CPU time over `method`), and an
///        exception becomes a run that did not run, with the reason in its message.
RegistrationRun
timedRun(const std::string& name, const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& source,
         const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& target,
         const std::function<void(RegistrationRun&)>& method);

/// x, y, z of a cloud in double, one column per point.
template <typename PointT>
Eigen::Matrix3Xd
cloudToMatrix(const pcl::PointCloud<PointT>& cloud)
{
  Eigen::Matrix3Xd m(3, static_cast<Eigen::Index>(cloud.size()));
  for (std::size_t i = 0; i < cloud.size(); ++i)
    m.col(static_cast<Eigen::Index>(i)) = cloud[i].getVector3fMap().template cast<double>();
  return m;
}

/// Copies x, y, z of any point cloud into a PointXYZ cloud (skipping non-finite points).
template <typename PointT>
pcl::PointCloud<pcl::PointXYZ>::Ptr
toXYZ(const pcl::PointCloud<PointT>& cloud)
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr out(new pcl::PointCloud<pcl::PointXYZ>);
  out->reserve(cloud.size());
  for (const auto& p : cloud)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
      out->push_back(pcl::PointXYZ(p.x, p.y, p.z));
  return out;
}

}  // namespace evaluation
}  // namespace pcl_ls3d
