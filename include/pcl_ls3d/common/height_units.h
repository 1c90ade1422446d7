#pragma once
/// \file height_units.h
/// \brief Heights in the plan unit. A compound CRS can store plan coordinates in metres and
///        heights in US survey feet (PDAL's autzen-bmx: NAD83 / Oregon LCC + NAVD88 height in
///        ftUS). Rotations, normals and residuals need one unit, so the pair tools and the strip
///        adjustment work in "working coordinates" (heights multiplied by plan units per height
///        unit, maps::planUnitsPerHeightUnit()) and give transformations and written clouds back
///        in the files' own units.
///
/// Local clouds share the target's origin o (file = local + o); the working origin is
/// targetToWorking(o), and a source point's working height is f_s (z + o_z) - f_t o_z.

#include <pcl/point_cloud.h>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace pcl_ls3d {

/// \brief Plan units per height unit of the target (reference) and source (epoch) files.
struct HeightUnits
{
  double target = 1.0;
  double source = 1.0;

  /// Both sides in one file's units (a strip corrected in its own file, a LAS source moved
  /// with its own header).
  static HeightUnits
  ofOneFile(double factor)
  {
    return {factor, factor};
  }

  /// True when either file's heights are converted.
  bool
  converts() const
  {
    return target != 1.0 || source != 1.0;
  }

  /// A transformation between working coordinates as it applies to the files' coordinates:
  /// S_t⁻¹ T S_s with S = diag(1, 1, factor, 1).
  Eigen::Matrix4d
  toFiles(const Eigen::Matrix4d& T_working) const;

  /// A transformation between the files' coordinates (a -truth) in working coordinates.
  Eigen::Matrix4d
  toWorking(const Eigen::Matrix4d& T_files) const;

  /// A point of the target's file in working coordinates (the height times `target`).
  Eigen::Vector3d
  targetToWorking(const Eigen::Vector3d& p) const
  {
    return {p.x(), p.y(), p.z() * target};
  }

  /// A point of the source, untransformed, in working coordinates back in its file's units.
  Eigen::Vector3d
  sourceToFile(const Eigen::Vector3d& p) const
  {
    return {p.x(), p.y(), p.z() / source};
  }
};

/// \brief What a report says about converted heights: {"plan_units_per_height_unit": {"target",
///        "source"}, "note": which figures are in working coordinates}; null when nothing was
///        converted.
nlohmann::json
heightUnitsJson(const HeightUnits& heights);

/// \brief Converts the heights of a cloud held in local coordinates around the file origin
///        \a origin_z (target's height unit) into working coordinates around the working origin:
///        z' = factor (z + origin_z) - target_factor origin_z.
template <typename PointT>
void
heightsToWorking(pcl::PointCloud<PointT>& cloud, double factor, double target_factor, double origin_z)
{
  const double shift = (factor - target_factor) * origin_z;
  for (auto& p : cloud)
    p.z = static_cast<float>(factor * p.z + shift);
}

/// \brief The inverse of heightsToWorking(): working local heights back in the file's units.
template <typename PointT>
void
heightsToFile(pcl::PointCloud<PointT>& cloud, double factor, double target_factor, double origin_z)
{
  const double shift = (factor - target_factor) * origin_z;
  for (auto& p : cloud)
    p.z = static_cast<float>((p.z - shift) / factor);
}

/// \brief A pair loaded around the target file's origin \a file_origin (the source in the
///        target's origin) into working coordinates; returns the working origin.
template <typename PointT>
Eigen::Vector3d
pairToWorking(const HeightUnits& h, const Eigen::Vector3d& file_origin, pcl::PointCloud<PointT>& target,
              pcl::PointCloud<PointT>& source)
{
  heightsToWorking(target, h.target, h.target, file_origin.z());
  heightsToWorking(source, h.source, h.target, file_origin.z());
  return h.targetToWorking(file_origin);
}

}  // namespace pcl_ls3d
