#include <pcl_ls3d/adjustment/report_json.h>
#include <pcl_ls3d/io/json_text.h>

#include <nlohmann/json.hpp>

#include <cmath>

namespace pcl_ls3d {

namespace {

using nlohmann::json;

json
finiteOrNull(double v)
{
  return std::isfinite(v) ? json(v) : json(nullptr);
}

template <typename Matrix>
json
rowsJson(const Matrix& M)
{
  json rows = json::array();
  for (Eigen::Index a = 0; a < M.rows(); ++a) {
    json row = json::array();
    for (Eigen::Index b = 0; b < M.cols(); ++b)
      row.push_back(M(a, b));
    rows.push_back(row);
  }
  return rows;
}

json
vectorJson(const Eigen::Vector3d& v)
{
  return {v.x(), v.y(), v.z()};
}

/// Per parameter name: values, σ (null when not finite), determinable and fixed flags.
void
addParameters(const AdjustmentReport& r, json& j)
{
  const auto& names = similarityParameterNames();
  json params, sigmas, formal, determinable, fixed;
  for (std::size_t i = 0; i < 7; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    params[names[i]] = r.parameters[k];
    sigmas[names[i]] = finiteOrNull(r.sigmas[k]);
    formal[names[i]] = finiteOrNull(r.sigmas_formal[k]);
    determinable[names[i]] = r.determinable[i];
    fixed[names[i]] = r.fixed[i];
  }
  j["parameters"] = params;
  j["parameters_note"] = "reduced frame: x_t - local_origin = t + m R (x_s - local_origin_source)";
  j["sigmas"] = sigmas;
  j["sigmas_formal"] = formal;
  j["determinable"] = determinable;
  j["fixed"] = fixed;
  j["correlation"] = rowsJson(r.correlation);
  j["qxx"] = rowsJson(r.qxx);
  j["covariance"] = rowsJson(r.covariance);
}

json
qualityJson(const QualityFigures& q)
{
  json j = {{"trustworthy", q.trustworthy},
            {"expected_noise", q.expected_noise},
            {"noise_yardstick", q.noise_yardstick},
            {"source_noise", q.source_noise},
            {"target_noise", q.target_noise},
            {"sigma0_ratio", q.sigma0_ratio},
            {"coverage", q.coverage},
            {"rejected_fraction", q.rejected_fraction},
            {"movement", q.movement},
            {"position_sigma", q.position_sigma}};
  if (q.held_out_scale_tested)
    j["held_out_scale"] = {{"estimate", q.held_out_scale},
                           {"sigma", q.held_out_scale_sigma},
                           {"z", q.held_out_scale_z},
                           {"effect", q.held_out_scale_effect}};
  return j;
}

json
logJson(const AdjustmentReport& r)
{
  json log = json::array();
  for (const auto& it : r.log)
    log.push_back({{"iteration", it.iteration},
                   {"sigma0", it.sigma0},
                   {"observations_used", it.observations_used},
                   {"observations_rejected", it.observations_rejected},
                   {"max_angle_change", it.max_angle_change},
                   {"translation_change", it.translation_change},
                   {"scale_change", it.scale_change},
                   {"extrapolated", it.extrapolated}});
  return log;
}

}  // namespace

std::string
adjustmentReportJson(const AdjustmentReport& r, bool converged, const ReportFrame& frame, int indent)
{
  json j;
  j["transformation"] = rowsJson(frame.transformation);
  j["converged"] = converged;
  j["termination"] = terminationTypeToString(r.termination);
  j["message"] = r.message;
  j["iterations"] = r.iterations;
  j["sigma0"] = r.sigma0;
  j["rule"] = r.rule_name;
  j["estimator"] = r.estimator_name;
  addParameters(r, j);
  j["precision_model"] = r.precision_model;
  j["source_noise"] = r.source_noise;
  j["quality"] = qualityJson(r.quality);
  j["log"] = logJson(r);
  j["observations_used"] = r.observations_used;
  j["observations_rejected"] = r.observations_rejected;
  j["correspondences"] = r.correspondences;
  j["source_points_used"] = r.source_points;
  j["redundancy"] = r.redundancy;
  j["local_origin"] = vectorJson(r.local_origin_target + frame.origin);
  j["local_origin_source"] = vectorJson(r.local_origin_source + frame.origin);
  j["cloud_origin"] = vectorJson(frame.cloud_origin);
  return io::toJsonText(j, indent);
}

}  // namespace pcl_ls3d
