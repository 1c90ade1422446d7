#pragma once
/// \file comparison_report.h
/// \brief The one table and the JSON document that pcl_ls3d_compare and benchmark_registration
///        print for a set of RegistrationRun rows (same columns, same units everywhere).

#include <pcl_ls3d/common/height_units.h>
#include <pcl_ls3d/evaluation/registration_run.h>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// \brief What was compared (written into the JSON next to the rows).
struct ComparisonContext
{
  std::string source, target;                             ///< file names or a generator description
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();       ///< common local origin (working = local + origin)
  HeightUnits heights;                                    ///< working coordinates: heights × factor
  Eigen::Vector3d file_origin = Eigen::Vector3d::Zero();  ///< origin in the target file's units
  std::size_t source_points = 0, target_points = 0;
  bool has_truth = false;
  double rms_max_distance = 0.0;            ///< [unit] neighbour cut-off of the RMS column
  std::string unit = "m";                   ///< the data's length unit (CRS), or "units"
  std::string pcl_settings, ls3d_settings;  ///< describe() of the settings used
};

/// \brief Fixed-width text table, one row per run. Columns: method, iterations, wall time [s],
///        CPU time [s] (all threads), converged, how it stopped (RegistrationRun::stop, cut to
///        10 characters), trusted (the method's hasConverged()), RMS of NN distances [unit],
///        σ0 [unit]; with truth also mean / max displacement error over the source points, max
///        over the source bbox corners, and the parameter errors (tx, ty, tz, φ, ω, κ [µrad],
///        m [ppm]); lengths of errors in mm when `unit` is "m", else in `unit` (3 digits).
///        A figure a run does not have (no estimate, no σ0) is "-".
std::string
formatComparisonTable(const std::vector<RegistrationRun>& runs, bool with_truth,
                      const std::string& unit = "m");

/// \brief JSON document {"context": {...}, "methods": [...]} in context.unit, s and rad; each
///        method has its transformation in local working coordinates and in the files'
///        coordinates (4×4 row-major; HeightUnits::toFiles()). A figure a run does not have is
///        null (a run without an estimate: every figure).
std::string
comparisonJson(const std::vector<RegistrationRun>& runs, const ComparisonContext& context);

}  // namespace evaluation
}  // namespace pcl_ls3d
