#pragma once
/// \file report_output.h
/// \brief The strip adjustment report for people and programs: a readable summary (per strip
///        the correction with σ, per overlap the discrepancies before → after next to the
///        strips' own noise) and the JSON document the tool writes with -json.

#include <pcl_ls3d/strips/strip_adjustment_report.h>

#include <string>

namespace pcl_ls3d {
namespace strips {

/// The report as JSON text: how it ended, strips, overlaps, log, notes, covariance, timings.
/// \a plan_units_per_height_unit: the factor the strips' heights were adjusted with
/// (heightFactor()); the parameters, origins and transformations are then in those working
/// coordinates, which the JSON says.
std::string
reportJson(const StripAdjustmentReport& report, int indent = 2, double plan_units_per_height_unit = 1.0);

/// Summary tables for a terminal (angles in mrad, m − 1 in ppm, lengths in the data's unit).
std::string
reportSummary(const StripAdjustmentReport& report, const std::string& unit = "m");

}  // namespace strips
}  // namespace pcl_ls3d
