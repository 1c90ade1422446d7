#pragma once
/// \file report_json.h
/// \brief An AdjustmentReport as the JSON document pcl_ls3d_register writes with -json, so a user
///        of the C++ API can produce the same report: the transformation in input coordinates,
///        how the adjustment ended, parameters with σ, Qxx, covariance and correlation,
///        the quality figures, the iteration log and the local origins.

#include <pcl_ls3d/adjustment/adjustment_report.h>

#include <Eigen/Core>

#include <string>

namespace pcl_ls3d {

/// \brief Where the report's reduced frame lies in the files' coordinates.
struct ReportFrame
{
  /// SOURCE → TARGET in input coordinates (what "transformation" says, 4 × 4 row-major).
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();
  /// Added to the report's local origins (the working origin of the clouds the adjustment saw).
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  /// The origin of a written cloud's coordinates ("cloud_origin").
  Eigen::Vector3d cloud_origin = Eigen::Vector3d::Zero();
};

/// \brief The report as JSON text (indent as nlohmann's dump: −1 one line). Non-finite σ are null.
/// \param[in] converged what "converged" says (pcl::Registration::hasConverged())
std::string
adjustmentReportJson(const AdjustmentReport& report, bool converged, const ReportFrame& frame,
                     int indent = -1);

}  // namespace pcl_ls3d
