// Plan and state files of a distributed strip adjustment (strip_files.h), as JSON: doubles are
// written with round-trip precision, so reading them back gives the same bits.
#include <pcl_ls3d/strips/strip_files.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace pcl_ls3d {
namespace strips {

namespace {

using json = nlohmann::json;
constexpr int kVersion = 2;  // 2: heights in the plan unit (HeightUnits)

json
vec(const Eigen::VectorXd& v)
{
  return std::vector<double>(v.data(), v.data() + v.size());
}

template <int N>
Eigen::Matrix<double, N, 1>
fixed(const json& j)
{
  const std::vector<double> v = j.get<std::vector<double>>();
  Eigen::Matrix<double, N, 1> out;
  for (int k = 0; k < N; ++k)
    out[k] = v.at(static_cast<std::size_t>(k));
  return out;
}

json
settingsJson(const StripAdjustmentSettings& s)
{
  return {{"footprint_cell", s.footprint_cell},
          {"min_overlap_area", s.min_overlap_area},
          {"min_overlap_observations", s.min_overlap_observations},
          {"stable_classes", std::vector<int>(s.stable_classes.begin(), s.stable_classes.end())},
          {"roughness_factor", s.roughness_factor},
          {"observation_spacing", s.observation_spacing},
          {"max_observations", s.max_observations},
          {"both_directions", s.both_directions},
          {"model", parameterModelName(s.model)},
          {"rule", static_cast<int>(s.rule)},
          {"estimator", toString(s.estimator)},
          {"max_distance", s.max_distance},
          {"reference_strips", s.reference_strips},
          {"soft_datum", s.soft_datum},
          {"soft_sigmas", vec(s.soft_sigmas)},
          {"max_iterations", s.adjustment.max_iterations},
          {"angle_epsilon", s.adjustment.angle_epsilon},
          {"translation_epsilon", s.adjustment.translation_epsilon},
          {"scale_epsilon", s.adjustment.scale_epsilon},
          {"freeze_sigma_fraction", s.adjustment.freeze_sigma_fraction},
          {"coarse_observations", s.adjustment.coarse_observations},
          {"determinability_threshold", s.adjustment.determinability_threshold},
          {"spatial_precision", s.adjustment.spatial_precision},
          {"precision_cell", s.adjustment.precision_cell},
          {"test_held_out", s.test_held_out},
          {"held_out_z", std::isfinite(s.adjustment.held_out_z) ? json(s.adjustment.held_out_z)
                                                                : json(nullptr)},  // null: inf
          {"held_out_noise_factor", s.adjustment.held_out_noise_factor}};
}

StripAdjustmentSettings
settingsOf(const json& j)
{
  StripAdjustmentSettings s;
  s.footprint_cell = j.at("footprint_cell");
  s.min_overlap_area = j.at("min_overlap_area");
  s.min_overlap_observations = j.at("min_overlap_observations");
  s.stable_classes.clear();
  for (int c : j.at("stable_classes").get<std::vector<int>>())
    s.stable_classes.insert(static_cast<std::uint8_t>(c));
  s.roughness_factor = j.at("roughness_factor");
  s.observation_spacing = j.at("observation_spacing");
  s.max_observations = j.at("max_observations");
  s.both_directions = j.at("both_directions");
  parseParameterModel(j.at("model").get<std::string>(), s.model);
  s.rule = static_cast<ConjugateRuleType>(j.at("rule").get<int>());
  if (!parseRobustEstimatorChoice(j.at("estimator").get<std::string>(), s.estimator))
    throw std::runtime_error("unknown estimator " + j.at("estimator").get<std::string>());
  s.max_distance = j.at("max_distance");
  s.reference_strips = j.at("reference_strips").get<std::vector<int>>();
  s.soft_datum = j.at("soft_datum");
  s.soft_sigmas = fixed<7>(j.at("soft_sigmas"));
  s.adjustment.max_iterations = j.at("max_iterations");
  s.adjustment.angle_epsilon = j.at("angle_epsilon");
  s.adjustment.translation_epsilon = j.at("translation_epsilon");
  s.adjustment.scale_epsilon = j.at("scale_epsilon");
  s.adjustment.freeze_sigma_fraction = j.at("freeze_sigma_fraction");
  s.adjustment.coarse_observations = j.at("coarse_observations");
  s.adjustment.determinability_threshold = j.at("determinability_threshold");
  s.adjustment.spatial_precision = j.at("spatial_precision");
  s.adjustment.precision_cell = j.at("precision_cell");
  // Absent in plans written before the held-out test: its defaults.
  s.test_held_out = j.value("test_held_out", s.test_held_out);
  if (j.contains("held_out_z"))
    s.adjustment.held_out_z = j.at("held_out_z").is_null() ? std::numeric_limits<double>::infinity()
                                                           : j.at("held_out_z").get<double>();
  s.adjustment.held_out_noise_factor = j.value("held_out_noise_factor", s.adjustment.held_out_noise_factor);
  return s;
}

json
planJson(const StripPlan& p)
{
  json strips = json::array();
  for (const PlannedStrip& s : p.strips)
    strips.push_back({{"name", s.name},
                      {"point_source_id", s.point_source_id},
                      {"origin", vec(s.origin)},
                      {"points", s.points},
                      {"observable", s.observable},
                      {"withheld", s.excluded.withheld},
                      {"synthetic", s.excluded.synthetic},
                      {"density", s.density},
                      {"radius", s.radius},
                      {"part", s.part},
                      {"reference", s.reference},
                      {"classified", s.classified}});
  json overlaps = json::array();
  for (const Overlap& o : p.overlaps)
    overlaps.push_back({{"i", o.i},
                        {"j", o.j},
                        {"common_cells", o.common_cells},
                        {"area", o.area},
                        {"points_i", o.points_i},
                        {"points_j", o.points_j},
                        {"used", o.used},
                        {"skip_reason", o.skip_reason}});
  return {{"settings", settingsJson(p.settings)},
          {"block_origin", vec(p.block_origin)},
          {"strips", strips},
          {"grid",
           {{"min_x", p.grid.min_x},
            {"max_y", p.grid.max_y},
            {"cell", p.grid.cell},
            {"cols", p.grid.cols},
            {"rows", p.grid.rows}}},
          {"overlaps", overlaps},
          {"precision_cell", p.precision_cell},
          {"notes", p.notes}};
}

StripPlan
planOf(const json& j)
{
  StripPlan p;
  p.settings = settingsOf(j.at("settings"));
  p.block_origin = fixed<3>(j.at("block_origin"));
  for (const json& s : j.at("strips")) {
    PlannedStrip q;
    q.name = s.at("name");
    q.point_source_id = s.at("point_source_id");
    q.origin = fixed<3>(s.at("origin"));
    q.points = s.at("points");
    q.observable = s.at("observable");
    q.excluded.withheld = s.at("withheld");
    q.excluded.synthetic = s.at("synthetic");
    q.density = s.at("density");
    q.radius = s.at("radius");
    q.part = s.at("part");
    q.reference = s.at("reference");
    q.classified = s.at("classified");
    p.strips.push_back(q);
  }
  const json& g = j.at("grid");
  p.grid.min_x = g.at("min_x");
  p.grid.max_y = g.at("max_y");
  p.grid.cell = g.at("cell");
  p.grid.cols = g.at("cols");
  p.grid.rows = g.at("rows");
  for (const json& o : j.at("overlaps")) {
    Overlap q;
    q.i = o.at("i");
    q.j = o.at("j");
    q.common_cells = o.at("common_cells");
    q.area = o.at("area");
    q.points_i = o.at("points_i");
    q.points_j = o.at("points_j");
    q.used = o.at("used");
    q.skip_reason = o.at("skip_reason");
    p.overlaps.push_back(q);
  }
  p.precision_cell = j.at("precision_cell");
  p.notes = j.at("notes").get<std::vector<std::string>>();
  return p;
}

bool
writeJson(const std::string& path, const json& j, std::string& error)
{
  std::ofstream out(path, std::ios::trunc);
  if (!out || !(out << j.dump(1) << '\n') || !out.flush()) {
    error = "cannot write " + path;
    return false;
  }
  return true;
}

bool
readJson(const std::string& path, json& j, std::string& error)
{
  std::ifstream in(path);
  if (!in) {
    error = "cannot open " + path;
    return false;
  }
  try {
    in >> j;
    if (j.at("version").get<int>() != kVersion)
      throw std::runtime_error("unsupported version");
  } catch (const std::exception& e) {
    error = path + ": " + e.what();
    return false;
  }
  return true;
}

}  // namespace

LoadedStrips
PlanFile::block() const
{
  LoadedStrips b;
  b.inputs = inputs;
  b.sources = sources;
  b.block_origin = plan.block_origin;
  b.crs_wkt = crs_wkt;
  b.unassigned = unassigned;
  b.notes = load_notes;
  return b;
}

bool
writePlanFile(const std::string& path, const PlanFile& f, std::string& error)
{
  json inputs = json::array(), sources = json::array();
  for (const InputFile& in : f.inputs) {
    json ps = json::array();
    for (const auto& kv : in.point_sources)
      ps.push_back({kv.first, kv.second});
    inputs.push_back({{"path", in.path},
                      {"format", in.format},
                      {"crs_wkt", in.crs_wkt},
                      {"points", in.points},
                      {"point_sources", ps}});
  }
  for (const StripSource& s : f.sources)
    sources.push_back({{"name", s.name},
                       {"point_source_id", s.point_source_id},
                       {"files", s.files},
                       {"file_origin", vec(s.file_origin)}});
  const json j = {{"version", kVersion},
                  {"plan", planJson(f.plan)},
                  {"load",
                   {{"split", f.load.split_by_point_source},
                    {"exclude_withheld", f.load.exclude_withheld},
                    {"exclude_synthetic", f.load.exclude_synthetic}}},
                  {"inputs", inputs},
                  {"sources", sources},
                  {"crs_wkt", f.crs_wkt},
                  {"unassigned", f.unassigned},
                  {"load_notes", f.load_notes},
                  {"output_dir", f.output_dir},
                  {"keep_files", f.keep_files},
                  {"json_path", f.json_path},
                  {"maps_dir", f.maps_dir},
                  {"bands", {f.band_inner, f.band_outer}},
                  {"map_format", maps::mapFormatName(f.map_format)}};
  return writeJson(path, j, error);
}

bool
readPlanFile(const std::string& path, PlanFile& f, std::string& error)
{
  json j;
  if (!readJson(path, j, error))
    return false;
  try {
    f = PlanFile();
    f.plan = planOf(j.at("plan"));
    const json& l = j.at("load");
    f.load.split_by_point_source = l.at("split");
    f.load.exclude_withheld = l.at("exclude_withheld");
    f.load.exclude_synthetic = l.at("exclude_synthetic");
    for (const json& in : j.at("inputs")) {
      InputFile i;
      i.path = in.at("path");
      i.format = in.at("format");
      i.crs_wkt = in.at("crs_wkt");
      i.points = in.at("points");
      for (const json& ps : in.at("point_sources"))
        i.point_sources[ps.at(0).get<int>()] = ps.at(1).get<std::size_t>();
      f.inputs.push_back(i);
    }
    for (const json& s : j.at("sources"))
      f.sources.push_back({s.at("name"), s.at("point_source_id"), s.at("files").get<std::vector<int>>(),
                           fixed<3>(s.at("file_origin"))});
    f.crs_wkt = j.at("crs_wkt");
    f.unassigned = j.at("unassigned");
    f.load_notes = j.at("load_notes").get<std::vector<std::string>>();
    f.output_dir = j.at("output_dir");
    f.keep_files = j.at("keep_files");
    f.json_path = j.at("json_path");
    f.maps_dir = j.at("maps_dir");
    f.band_inner = j.at("bands").at(0);
    f.band_outer = j.at("bands").at(1);
    // Plan files written before the option existed drew PNG.
    if (j.contains("map_format") &&
        !maps::parseMapFormat(j.at("map_format").get<std::string>(), f.map_format))
      throw std::runtime_error("unknown map_format " + j.at("map_format").dump());
  } catch (const std::exception& e) {
    error = path + ": " + e.what();
    return false;
  }
  return true;
}

bool
writeState(const std::string& path, const BlockState& s, std::string& error)
{
  json values = json::array(), log = json::array();
  for (const Vector7d& v : s.values)
    values.push_back(vec(v));
  for (const BlockIterationRecord& r : s.log)
    log.push_back({r.iteration, r.observations, r.used, r.sigma0, r.max_angle_change,
                   r.max_translation_change, r.max_scale_change, r.coarse, r.frozen});
  if (!writeMatrix(path + ".qxx", s.qxx, error))  // 7N × 7N: binary, beside the JSON
    return false;
  const json j = {{"version", kVersion},
                  {"phase", static_cast<int>(s.phase)},
                  {"iteration", s.iteration},
                  {"values", values},
                  {"sigma0", s.sigma0},
                  {"soft_sigma_obs", s.soft_sigma_obs},
                  {"fixed", s.fixed},
                  {"determinable", s.determinable},
                  {"redundancy", s.redundancy},
                  {"observations", s.observations},
                  {"coarse", s.coarse},
                  {"frozen", s.frozen},
                  {"termination", static_cast<int>(s.termination)},
                  {"message", s.message},
                  {"log", log}};
  return writeJson(path, j, error);
}

bool
readState(const std::string& path, BlockState& s, std::string& error)
{
  json j;
  if (!readJson(path, j, error))
    return false;
  try {
    s = BlockState();
    s.phase = static_cast<BlockState::Phase>(j.at("phase").get<int>());
    s.iteration = j.at("iteration");
    for (const json& v : j.at("values"))
      s.values.push_back(fixed<7>(v));
    s.sigma0 = j.at("sigma0");
    s.soft_sigma_obs = j.at("soft_sigma_obs");
    if (!readMatrix(path + ".qxx", s.qxx, error))
      return false;
    s.fixed = j.at("fixed").get<std::vector<bool>>();
    s.determinable = j.at("determinable").get<std::vector<bool>>();
    s.redundancy = j.at("redundancy");
    s.observations = j.at("observations");
    s.coarse = j.at("coarse");
    s.frozen = j.at("frozen");
    s.termination = static_cast<TerminationType>(j.at("termination").get<int>());
    s.message = j.at("message");
    for (const json& r : j.at("log"))
      s.log.push_back({r.at(0), r.at(1), r.at(2), r.at(3), r.at(4), r.at(5), r.at(6), r.at(7), r.at(8)});
  } catch (const std::exception& e) {
    error = path + ": " + e.what();
    return false;
  }
  return true;
}

}  // namespace strips
}  // namespace pcl_ls3d
