#pragma once
/// \file ls3d_method.h
/// \brief Runs pcl_ls3d::LeastSquaresSurfaceMatching with one conjugate-point rule on the same
///        input and with the same timing and result row as the PCL methods (pcl_methods.h).

#include <pcl_ls3d/adjustment/parameter_block.h>
#include <pcl_ls3d/evaluation/registration_run.h>
#include <pcl_ls3d/rules/conjugate_rule.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <string>

namespace pcl_ls3d {
namespace evaluation {

/// "LS3D-LND", "LS3D-LZD", "LS3D-ICP".
std::string
ls3dMethodName(ConjugateRuleType rule);

/// \brief Settings handed to LS3D; everything else keeps the class defaults (Zuo's 0/1 weight at
///        6σ0, angle ε 1e-6 rad, quality gate on).
struct Ls3dMethodSettings
{
  /// [m] same as the PCL methods; <= 0 = the class default (unlimited with the automatic,
  /// data-derived reach), i.e. what a user who sets nothing gets.
  double max_correspondence_distance = 2.0;
  int max_iterations = 30;            ///< LS3D default; <= 0 = the class default
  double source_thinning = 0.0;       ///< [m] voxel edge, 0 = every source point
  double translation_epsilon = 1e-5;  ///< [m] stop when the translation step is below
                                      ///< (the class default)
  /// RIGID_6 is the class default (like the ICP it replaces); SIMILARITY_7 frees the scale.
  ParameterModel model = ParameterModel::RIGID_6;

  /// One line listing every value, for tables and docs; lengths labelled `unit` (the data's).
  std::string
  describe(const std::string& unit = "m") const;

  /// The same settings for data in another length unit: the correspondence distance, thinning
  /// and translation step divided by \a metres_per_unit (as PclMethodSettings::inUnit()).
  Ls3dMethodSettings
  inUnit(double metres_per_unit) const;
};

/// \brief Aligns source to target from the identity; never throws. The transform is taken from
///        the report (double) when the solution is usable, else from getFinalTransformation().
RegistrationRun
runLs3d(ConjugateRuleType rule, const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& source,
        const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& target, const Ls3dMethodSettings& settings = {});

}  // namespace evaluation
}  // namespace pcl_ls3d
