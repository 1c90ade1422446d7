#include <pcl_ls3d/evaluation/segmentation_classes.h>
#include <pcl_ls3d/io/json_text.h>
#include <pcl_ls3d/synth/truth_json.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <map>
#include <sys/stat.h>

namespace pcl_ls3d {
namespace synth {

namespace {

using nlohmann::json;

json
vec(const Eigen::Vector3d& v)
{
  return json::array({v.x(), v.y(), v.z()});
}

json
vec2(const Eigen::Vector2d& v)
{
  return json::array({v.x(), v.y()});
}

json
rows(const Eigen::Matrix4d& T)
{
  json out = json::array();
  for (int r = 0; r < 4; ++r)
    out.push_back(json::array({T(r, 0), T(r, 1), T(r, 2), T(r, 3)}));
  return out;
}

json
params(const SimilarityTransform& T)
{
  json p;
  p["tx"] = T.t.x();
  p["ty"] = T.t.y();
  p["tz"] = T.t.z();
  p["phi"] = T.phi;
  p["omega"] = T.omega;
  p["kappa"] = T.kappa;
  p["m"] = T.m;
  return p;
}

/// The transform block described in truth_json.h.
json
transformJson(const SimilarityTransform& local, const Eigen::Vector3d& origin)
{
  const Eigen::Matrix4d G = localToGlobal(local.matrix(), origin, origin);
  json j;
  j["transformation"] = rows(G);
  j["transformation_local"] = rows(local.matrix());
  j["parameters"] = params(local);
  j["parameters_frame_origin"] = vec(origin);
  SimilarityTransform global = local;  // same angles and scale; only t moves with the origin
  global.t = G.topRightCorner<3, 1>();
  j["parameters_global"] = params(global);
  return j;
}

json
header(const char* generator, std::uint32_t seed, const Eigen::Vector3d& origin)
{
  json j;
  j["generator"] = generator;
  j["seed"] = seed;
  j["origin"] = vec(origin);
  j["convention"] = "x' = t + m R_Y(phi) R_X(omega) R_Z(kappa) x; angles in rad; global = local + origin";
  return j;
}

json
classCounts(const pcl::PointCloud<PointLiDAR>& cloud)
{
  std::map<int, std::size_t> c;
  for (const auto& p : cloud)
    ++c[p.classification];
  json j = json::object();
  for (const auto& kv : c)
    j[std::to_string(kv.first)] = kv.second;
  return j;
}

json
box(const Eigen::AlignedBox2d& b, const Eigen::Vector3d& o)
{
  return json::array({b.min().x() + o.x(), b.min().y() + o.y(), b.max().x() + o.x(), b.max().y() + o.y()});
}

}  // namespace

std::string
truthJson(const RegistrationPair& pair, const RegistrationPairSettings& s)
{
  json j = header("pcl_ls3d::synth::makeRegistrationPair", s.seed, pair.origin);
  j.update(transformJson(pair.truth, pair.origin));
  j["maps"] = "source -> target";
  j["settings"] = {{"size_x", s.size_x},
                   {"size_y", s.size_y},
                   {"source_density", s.source_density},
                   {"target_density", s.target_density},
                   {"overlap", s.overlap},
                   {"noise_sigma", s.noise_sigma},
                   {"buildings", s.buildings},
                   {"buildings_per_hectare", s.building_settings.per_hectare},
                   {"relief", s.relief},
                   {"wavelength", s.wavelength}};
  j["footprints_global_xy"] = {{"source", box(pair.source_footprint, pair.origin)},
                               {"target", box(pair.target_footprint, pair.origin)},
                               {"frame", "target; [xmin, ymin, xmax, ymax]"}};
  j["counts"] = {{"source", pair.source->size()},
                 {"target", pair.target->size()},
                 {"source_by_class", classCounts(*pair.source)},
                 {"target_by_class", classCounts(*pair.target)},
                 {"buildings", pair.surface ? pair.surface->buildings().buildings().size() : 0}};
  return io::toJsonText(j, 2);
}

std::string
truthJson(const StripBlock& block, const StripSettings& s)
{
  json j = header("pcl_ls3d::synth::makeStripBlock", s.seed, block.origin);
  j["maps"] = "each strip's observed coordinates -> true (reference) frame";
  j["settings"] = {{"num_strips", s.num_strips},
                   {"heading", s.heading},
                   {"strip_length", s.strip_length},
                   {"swath_width", s.swath_width},
                   {"side_overlap", s.side_overlap},
                   {"density", s.density},
                   {"pattern", s.pattern == ScanPattern::ZIGZAG ? "zigzag" : "parallel"},
                   {"speed", s.speed},
                   {"noise_sigma", s.noise_sigma},
                   {"buildings", s.buildings},
                   {"fix_first", s.fix_first},
                   {"shift_sigma", s.shift_sigma},
                   {"angle_sigma", s.angle_sigma},
                   {"scale_sigma", s.scale_sigma},
                   {"relief", s.relief},
                   {"wavelength", s.wavelength}};
  j["strips"] = json::array();
  for (const auto& st : block.strips) {
    json k = transformJson(st.transform, block.origin);
    k["point_source_id"] = st.point_source_id;
    k["fixed"] = st.fixed;
    k["centre"] = vec(st.centre + block.origin);
    k["t_centre"] = vec(st.t_centre);
    json fp = json::array();
    for (const auto& c : st.footprint)
      fp.push_back(vec2(c + block.origin.head<2>()));
    k["footprint_global_xy"] = fp;
    k["first_index"] = st.first_index;
    k["point_count"] = st.point_count;
    k["scan_lines"] = st.scan_lines;
    k["points_per_line"] = st.points_per_line;
    k["start_time"] = st.start_time;
    k["end_time"] = st.end_time;
    j["strips"].push_back(k);
  }
  j["counts"] = {{"points", block.cloud->size()}, {"by_class", classCounts(*block.cloud)}};
  return io::toJsonText(j, 2);
}

std::string
truthJson(const LiSurface& li, const LiSurfaceSettings& s)
{
  json j = header("pcl_ls3d::synth::makeLiSurface", s.seed, Eigen::Vector3d::Zero());
  j.update(transformJson(li.truth, Eigen::Vector3d::Zero()));
  j["maps"] = "mate (source) -> reference (target)";
  j["applied_to_mate"] = params(li.truth.inverse());
  j["settings"] = {{"grid_size", s.grid_size},
                   {"spacing", s.spacing},
                   {"relief", s.relief},
                   {"wavelength", s.wavelength},
                   {"noise_sigma", s.noise_sigma},
                   {"deformation_percent", s.deformation_percent},
                   {"deformation_c", s.deformation_c},
                   {"position", toString(s.position)},
                   {"noise_on_reference", s.noise_on_reference}};
  double mean = 0.0;
  for (int i : li.deformed_indices)
    mean += li.deformation[i];
  j["deformation"] = {{"percent", li.percent},
                      {"count", li.deformed_indices.size()},
                      {"mean", li.deformed_indices.empty() ? 0.0 : mean / li.deformed_indices.size()},
                      {"indices", li.deformed_indices},
                      {"mask", li.deformed}};
  j["counts"] = {{"reference", li.reference->size()}, {"mate", li.mate->size()}};
  return io::toJsonText(j, 2);
}

std::string
truthJson(const LabelledScene& scene, const SceneSettings& s)
{
  json j = header("pcl_ls3d::synth::makeScene", s.seed, scene.origin);
  j["settings"] = {{"size_x", s.size_x},
                   {"size_y", s.size_y},
                   {"density", s.density},
                   {"noise_sigma", s.noise_sigma},
                   {"relief", s.relief},
                   {"wavelength", s.wavelength},
                   {"buildings", s.buildings},
                   {"trees_per_hectare", s.trees_per_hectare},
                   {"shrubs_per_hectare", s.shrubs_per_hectare},
                   {"cars_per_hectare", s.cars_per_hectare},
                   {"power_line", s.power_line},
                   {"low_max", s.low_max},
                   {"medium_max", s.medium_max},
                   {"car_class", s.car_class}};
  j["classes"] = json::object();
  for (int code : {2, 3, 4, 5, 6, 14, 15})
    j["classes"][std::to_string(code)] = evaluation::lasClassName(code);
  j["classes"].emplace(std::to_string(s.car_class), "car (user-defined)");  // a standard code keeps its name
  j["counts"] = {{"points", scene.cloud->size()}, {"by_class", classCounts(*scene.cloud)}};
  j["objects"] = json::array();
  for (const auto& o : scene.objects)
    j["objects"].push_back({{"id", o.id},
                            {"type", toString(o.type)},
                            {"classification", o.classification},
                            {"position", vec(o.position + scene.origin)},
                            {"size", vec(o.size)},
                            {"heading", o.heading},
                            {"points", o.point_count}});
  return io::toJsonText(j, 2);
}

bool
writeTextFile(const std::string& path, const std::string& text, bool overwrite, std::string& error)
{
  struct stat st;
  if (!overwrite && ::stat(path.c_str(), &st) == 0) {
    error = path + " exists (use -overwrite)";
    return false;
  }
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) {
    error = "cannot open " + path + " for writing";
    return false;
  }
  f << text << '\n';
  if (!f) {
    error = "failed writing " + path;
    return false;
  }
  return true;
}

}  // namespace synth
}  // namespace pcl_ls3d
