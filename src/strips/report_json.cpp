// The strip adjustment report as JSON (strip_maps.h: reportJson).
#include <pcl_ls3d/strips/report_output.h>

#include <nlohmann/json.hpp>

#include <cmath>

namespace pcl_ls3d {
namespace strips {

namespace {

using json = nlohmann::json;

// JSON has no infinity: undeterminable σ are written as null.
json
number(double v)
{
  return std::isfinite(v) ? json(v) : json(nullptr);
}

json
vec(const Eigen::VectorXd& v)
{
  json a = json::array();
  for (Eigen::Index k = 0; k < v.size(); ++k)
    a.push_back(number(v[k]));
  return a;
}

json
matrix(const Eigen::MatrixXd& m)
{
  json a = json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    a.push_back(vec(m.row(r).transpose()));
  return a;
}

json
stats(const DiscrepancyStatistics& s)
{
  return {{"count", s.count},
          {"mean", s.mean},
          {"rms", s.rms},
          {"sigma_mad", s.sigma_mad},
          {"percentiles", {{"5", s.p05}, {"16", s.p16}, {"50", s.p50}, {"84", s.p84}, {"95", s.p95}}}};
}

const char* const kParameterNames[7] = {"tx", "ty", "tz", "phi", "omega", "kappa", "m"};

json
heldOut(const std::vector<HeldOutParameter>& held_out)
{
  json a = json::array();
  for (const HeldOutParameter& h : held_out)
    a.push_back({{"parameter", kParameterNames[h.parameter]},
                 {"estimate", number(h.estimate)},
                 {"sigma", number(h.sigma)},
                 {"sigma_formal", number(h.sigma_formal)},
                 {"z", number(h.z)},
                 {"effect", number(h.effect)},
                 {"own_noise", number(h.noise)},
                 {"significant", h.significant},
                 {"flagged", h.flagged}});
  return a;
}

json
strip(const StripResult& s)
{
  json flags_fixed = json::array(), flags_det = json::array();
  for (int q = 0; q < 7; ++q) {
    flags_fixed.push_back(s.fixed[static_cast<std::size_t>(q)]);
    flags_det.push_back(s.determinable[static_cast<std::size_t>(q)]);
  }
  return {{"name", s.name},
          {"point_source_id", s.point_source_id},
          {"origin", vec(s.origin)},
          {"points", s.points},
          {"observable", s.observable},
          {"excluded", {{"withheld", s.excluded.withheld}, {"synthetic", s.excluded.synthetic}}},
          {"reference", s.reference},
          {"adjusted", s.adjusted},
          {"parameters", vec(s.parameters)},
          {"sigmas", vec(s.sigmas)},
          {"sigmas_formal", vec(s.sigmas_formal)},
          {"fixed", flags_fixed},
          {"determinable", flags_det},
          {"transformation", matrix(s.transformation)},
          {"note", s.note},
          {"held_out", heldOut(s.held_out)}};
}

json
overlap(const OverlapResult& o, const StripAdjustmentReport& r)
{
  json j = {{"strips",
             {r.strips[static_cast<std::size_t>(o.i)].name, r.strips[static_cast<std::size_t>(o.j)].name}},
            {"indices", {o.i, o.j}},
            {"area", o.area},
            {"common_cells", o.common_cells},
            {"points", {o.points_i, o.points_j}},
            {"used", o.used}};
  if (!o.used) {
    j["skip_reason"] = o.skip_reason;
    return j;
  }
  j["observation_spacing"] = o.spacing;
  j["observations"] = o.observations;
  j["observations_used"] = o.used_observations;
  j["observations_rejected"] = o.observations - o.used_observations;
  j["sigma0"] = o.sigma0;
  j["sigma_surface"] = o.sigma_surface;
  j["discrepancy_before"] = stats(o.before);
  j["discrepancy_after"] = stats(o.after);
  j["own_noise"] = {stats(o.noise_i), stats(o.noise_j)};
  j["asked_translation"] = {{"count", o.asked.count},
                            {"t", {o.asked.t.x(), o.asked.t.y(), o.asked.t.z()}},
                            {"sigma", {o.asked.sigma.x(), o.asked.sigma.y(), o.asked.sigma.z()}}};
  return j;
}

}  // namespace

std::string
reportJson(const StripAdjustmentReport& r, int indent, double plan_units_per_height_unit)
{
  json j;
  j["termination"] = terminationTypeToString(r.termination);
  j["converged"] = r.converged();
  j["message"] = r.message;
  j["iterations"] = r.iterations;
  j["sigma0"] = r.sigma0;
  j["redundancy"] = r.redundancy;
  j["observations"] = r.observations;
  j["unknowns"] = r.unknowns;
  j["rule"] = r.rule;
  j["estimator"] = r.estimator;
  j["model"] = r.model;
  j["precision_model"] = r.precision_model;
  j["parameter_order"] = {"tx", "ty", "tz", "phi", "omega", "kappa", "m"};
  const bool converted = plan_units_per_height_unit != 1.0;
  j["parameter_frame"] = std::string("x' = origin + t + m R(phi, omega, kappa) (x - origin), per strip "
                                     "origin, file coordinates") +
                         (converted ? " with heights in the plan unit (see heights)" : "");
  if (converted)
    j["heights"] = {{"plan_units_per_height_unit", plan_units_per_height_unit},
                    {"note", "heights were multiplied by this factor for the adjustment: parameters, "
                             "origins, transformations and discrepancies are in working coordinates; "
                             "the corrected files keep their own units"}};
  j["block_origin"] = vec(r.block_origin);
  j["footprint_cell"] = r.footprint_cell;
  j["notes"] = r.notes;
  j["held_out_test"] = {{"tested", r.held_out.tested},
                        {"note", r.held_out.note},
                        {"statistic", number(r.held_out.statistic)},
                        {"dof", r.held_out.dof},
                        {"significant_strips", r.held_out.significant},
                        {"flagged_strips", r.held_out.flagged}};
  j["strips"] = json::array();
  for (const StripResult& s : r.strips)
    j["strips"].push_back(strip(s));
  j["overlaps"] = json::array();
  for (const OverlapResult& o : r.overlaps)
    j["overlaps"].push_back(overlap(o, r));
  j["log"] = json::array();
  for (const BlockIterationRecord& l : r.log)
    j["log"].push_back({{"iteration", l.iteration},
                        {"observations", l.observations},
                        {"used", l.used},
                        {"sigma0", l.sigma0},
                        {"max_angle_change", l.max_angle_change},
                        {"max_translation_change", l.max_translation_change},
                        {"max_scale_change", l.max_scale_change},
                        {"coarse", l.coarse},
                        {"frozen", l.frozen}});
  j["covariance"] = matrix(r.covariance);
  j["timings_s"] = r.timings_s;
  return j.dump(indent);
}

}  // namespace strips
}  // namespace pcl_ls3d
