#pragma once
/// \file surface_discrepancy.h
/// \brief Signed normal discrepancies between two overlapping clouds, for pairs without a
///        reference transform (e.g. two flight strips): how far each (transformed) source point
///        lies from the target surface along the target's local normal, and robust statistics
///        of those distances (median, σ_MAD = 1.4826 · MAD) before and after a registration.
///
/// Target planes are fitted once (PCA of the k nearest target points of every target point:
/// centroid c_j, normal n_j, surface variation λ0 / (λ0 + λ1 + λ2)). A source point y is
/// compared with the plane of its nearest target point j when |y − p_j| <= max_distance and the
/// plane is flat (variation <= max_variation, so vegetation and edges are left out):
/// d = n_j · (y − c_j). Normals point up (n_z >= 0) or, with `outward`, away from the target's
/// centroid (closed objects).
///
/// Not strips/discrepancies.h on purpose: that one measures with LS3D's own LND quadric (the
/// adjustment's observation), while a yardstick that compares LS3D with PCL's methods must not
/// share the surface model of one of the methods it judges.

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <cstddef>
#include <limits>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// \brief Robust statistics of the signed discrepancies of one transform.
struct DiscrepancyStats
{
  std::size_t points = 0;  ///< source points compared (within reach of a flat target plane)
  double median = std::numeric_limits<double>::quiet_NaN();     ///< [length]
  double sigma_mad = std::numeric_limits<double>::quiet_NaN();  ///< 1.4826 · median |d − median|
  double rms = std::numeric_limits<double>::quiet_NaN();        ///< of the raw distances
};

/// \brief Settings of the discrepancy measure.
struct DiscrepancySettings
{
  int k = 10;                   ///< target neighbours per plane
  double max_distance = 1.0;    ///< [length] reach from a source point to its nearest target point
  double max_variation = 0.02;  ///< flatness limit of the target plane (λ0 / Σλ)
  bool outward = false;         ///< false: normals up (airborne); true: away from the centroid
};

/// \brief The target's local planes, fitted once and reused for every transform.
class SurfaceDiscrepancy
{
public:
  using CloudXYZ = pcl::PointCloud<pcl::PointXYZ>;

  SurfaceDiscrepancy(const CloudXYZ::ConstPtr& target, const DiscrepancySettings& settings = {});

  /// Statistics of the discrepancies of the source points (one column per point) under T.
  DiscrepancyStats
  evaluate(const Eigen::Matrix3Xd& source_points, const Eigen::Matrix4d& T) const;

  /// Target points with a usable (flat) plane.
  std::size_t
  flatPlanes() const;

private:
  DiscrepancySettings settings_;
  CloudXYZ::ConstPtr target_;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree_;
  std::vector<Eigen::Vector3d> centroid_, normal_;
  std::vector<char> flat_;
};

}  // namespace evaluation
}  // namespace pcl_ls3d
