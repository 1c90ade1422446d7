/// \file pcl_ls3d_segment.cpp
/// \brief Multi-factor segmentation of a point cloud (IMRG, MRG or PCL region growing), with an
///        optional evaluation of all three against the reference labels of the input.
///
/// Output SEGMENTS.pcd (segments_file.h): every input point in input order, x y z float in the
/// local frame (origin in a "# pcl_ls3d origin" header line and the JSON report), label =
/// segment id + 1 (0 = in no segment, and every non-finite input point), rgba per segment, so
/// that pcl::io::loadPCDFile into pcl::PointXYZRGBL reads it.

#include "tool_arguments.h"
#include "tool_output.h"

#include <pcl_ls3d/common/voxel_index.h>
#include <pcl_ls3d/evaluation/object_metrics.h>
#include <pcl_ls3d/evaluation/reference_objects.h>
#include <pcl_ls3d/evaluation/segmentation_classes.h>
#include <pcl_ls3d/evaluation/segmentation_labels.h>
#include <pcl_ls3d/evaluation/segmentation_metrics.h>
#include <pcl_ls3d/evaluation/segmentation_report.h>
#include <pcl_ls3d/evaluation/segmentation_runner.h>
#include <pcl_ls3d/evaluation/segments_file.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/segmentation/dimensionality_features.h>
#include <pcl_ls3d/segmentation/object_classes.h>
#include <pcl_ls3d/stats/descriptive.h>
#include <pcl_ls3d/io/json_text.h>

#include <pcl/common/time.h>
#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>
#include <pcl/io/pcd_io.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace pcl::console;
using namespace pcl_ls3d;
using nlohmann::json;
namespace ev = pcl_ls3d::evaluation;

namespace {

const std::set<std::string> kValueOptions{"-o", "-mode", "-json", "-k", "-Nt", "-Mt", "-vt",
                                          "-dt", "-st", "-Vt", "-classes", "-threads",
                                          "-eval_min_size", "-min_fragment", "-level",
                                          "-object_radius"};
const std::set<std::string> kFlagOptions{"-evaluate", "-overwrite", "-h", "--help", "-help"};

void
printHelp(const char* prog)
{
  print_info("Multi-factor segmentation by improved multi-rule region growing (Wang et al. 2021).\n\n"
             "Syntax: %s INPUT [options]\n"
             "  INPUT              .las .pcd .ply .xyz/.txt (LAS classification / PCD label = reference)\n"
             "  -o SEGMENTS.pcd    every input point in input order: x y z float, local frame\n"
             "                     (file coordinate = x + origin; origin in the header line\n"
             "                     '# pcl_ls3d origin X Y Z' and the JSON), label = segment + 1\n"
             "                     (a header line marks the file: -evaluate refuses it)\n"
             "                     (0 = none, also for non-finite input points and pcl_rg's\n"
             "                     points in clusters under its minimum size), rgba per\n"
             "                     segment; pcl::io::loadPCDFile into pcl::PointXYZRGBL reads it\n"
             "  -mode imrg|mrg|pcl_rg   method for -o and the JSON report (default imrg)\n"
             "  -level objects|planes   IMRG/MRG output: whole objects (default) or the planes\n"
             "                     before merging (the paper's building-plane level)\n"
             "  -json REPORT.json  thresholds, dimensionality counts, segment counts, timings\n"
             "  -k kmin,kmax       optimal-neighbourhood range (default: class default 10,100)\n"
             "  -Nt deg, -Mt deg   normal / principal-direction angle thresholds\n"
             "  -vt m, -dt m, -st m, -Vt v   seed residual, merge distance, similarity and volume\n"
             "                     thresholds; negative or absent = adaptive (median, Baarda, k-means)\n"
             "  -evaluate          run IMRG, MRG, normals + pcl::RegionGrowing (clusters under\n"
             "                     its minimum size kept as one rest segment) and a voxel grid\n"
             "                     with IMRG's segment count on the same cloud; print the\n"
             "                     object-based P/R/F1 of Wang et al. 2021 sec. 4.1, valid segments\n"
             "                     per object and largest-segment share, and per-point P/R/F1 by\n"
             "                     majority mapping, against the reference labels\n"
             "  -classes SPEC      class groups, default ground=2,building=6,vegetation=3-5,wire=14\n"
             "                     (codes 0 and 1 are excluded unless a group names them)\n"
             "  -object_radius m   reference objects = connected components per class group at\n"
             "                     this radius (default: max(1, 2.5 x median point spacing))\n"
             "  -eval_min_size n   evaluate segments under n points as no segment (default 0);\n"
             "                     majority mapping rewards fragments, n = 30 matches pcl_rg's minimum\n"
             "  -min_fragment n    IMRG/MRG: segments under n points join the adjacent segment with\n"
             "                     the most k-NN links (default: class default; 0 = off, as the paper)\n"
             "  -threads n         OpenMP threads (default: all)\n"
             "  -overwrite         allow replacing existing output files\n"
             "pcl::RegionGrowing uses NormalEstimationOMP k 20, k 20, 10 deg, curvature 0.1, min 30.\n",
             prog);
}

/// Scans argv: exactly one positional INPUT, only known options, values present.
bool
checkArguments(int argc, char** argv, std::string& input, std::string& error)
{
  std::vector<std::string> positional;  // unknown, repeated or value-less options are refused
  if (!tools::splitArguments(argc, argv, 1, kValueOptions, kFlagOptions, positional, error))
    return false;
  if (positional.size() > 1)
    error = "more than one input given ('" + positional[0] + "', '" + positional[1] + "')";
  else if (positional.empty())
    error = "no input file given (see -h)";
  else
    input = positional[0];
  return error.empty();
}

/// Strict number (tool_arguments.h): the whole string must parse and be finite.
bool
parseNumber(int argc, char** argv, const char* name, double& value, std::string& error)
{
  return tools::numberOption(argc, argv, name, value, error);
}

bool
parseSettings(int argc, char** argv, ev::SegmentationRunSettings& s, std::string& error)
{
  std::string mode = "imrg";
  parse_argument(argc, argv, "-mode", mode);
  if (!ev::parseSegmentationMethod(mode, s.method)) {
    error = "unknown -mode '" + mode + "' (imrg, mrg or pcl_rg)";
    return false;
  }
  std::string level = "objects";
  parse_argument(argc, argv, "-level", level);
  if (level == "objects")
    s.level = ev::SegmentationLevel::Objects;
  else if (level == "planes")
    s.level = ev::SegmentationLevel::Planes;
  else {
    error = "unknown -level '" + level + "' (objects or planes)";
    return false;
  }
  std::string k;
  if (parse_argument(argc, argv, "-k", k) >= 0) {
    char *e1 = nullptr, *e2 = nullptr;
    const long a = std::strtol(k.c_str(), &e1, 10);
    const long b = (*e1 == ',') ? std::strtol(e1 + 1, &e2, 10) : 0;
    if (*e1 != ',' || !e2 || *e2 != '\0' || a < 3 || b < a || b > 65535) {
      error = "-k expects kmin,kmax with 3 <= kmin <= kmax, got '" + k + "'";
      return false;
    }
    s.k_min = static_cast<int>(a);
    s.k_max = static_cast<int>(b);
  }
  double threads = 0, min_fragment = -1;
  if (!parseNumber(argc, argv, "-min_fragment", min_fragment, error) ||
      !parseNumber(argc, argv, "-Nt", s.normal_angle_deg, error) ||
      !parseNumber(argc, argv, "-Mt", s.principal_angle_deg, error) ||
      !parseNumber(argc, argv, "-vt", s.residual_threshold, error) ||
      !parseNumber(argc, argv, "-dt", s.distance_threshold, error) ||
      !parseNumber(argc, argv, "-st", s.similarity_threshold, error) ||
      !parseNumber(argc, argv, "-Vt", s.volume_threshold, error) ||
      !parseNumber(argc, argv, "-threads", threads, error))
    return false;
  for (const char* o : {"-Nt", "-Mt"}) {
    double v = 1.0;
    parseNumber(argc, argv, o, v, error);
    if (!(v > 0.0 && v < 180.0)) {
      error = std::string(o) + " must be in (0, 180) degrees";
      return false;
    }
  }
  if (threads < 0 || threads != std::floor(threads)) {
    error = "-threads must be a non-negative integer";
    return false;
  }
  s.threads = static_cast<int>(threads);
  if (tools::optionValue(argc, argv, "-min_fragment")) {
    if (min_fragment < 0 || min_fragment != std::floor(min_fragment) || min_fragment > 1e9) {
      error = "-min_fragment must be a non-negative integer";
      return false;
    }
    s.min_fragment_size = static_cast<int>(min_fragment);
  }
  if (s.method == ev::SegmentationMethod::PclRegionGrowing && tools::optionValue(argc, argv, "-level")) {
    error = "-level applies to imrg and mrg, not to -mode pcl_rg";
    return false;
  }
  return s.isValid(&error);
}

/// Refuses an output equal to the input, an existing one without -overwrite, or one that cannot
/// be written (tool_arguments.h), before any work.
bool
checkOutput(const std::string& out, const std::string& input, bool overwrite, std::string& error)
{
  return tools::checkOutputFile(out, {input}, overwrite, error);
}

json
runToJson(const ev::SegmentationRun& r)
{
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json j;
  j["method"] = ev::toString(r.method);
  j["segments"] = r.segments.size();
  j["segments_before_merging"] = r.segments_before_merge;
  j["segments_after_merging"] = r.segments_after_merge;
  j["merges"] = r.merges;
  j["thresholds"] = {{"v_t_m", num(r.residual_threshold)}, {"d_t_m", num(r.distance_threshold)},
                     {"s_t_m", num(r.similarity_threshold)}, {"V_t", num(r.volume_threshold)},
                     {"distance_samples", r.distance_samples},
                     {"volume_samples", r.volume_samples}};
  j["spacing_m"] = num(r.spacing);
  j["growth_radius_m"] = num(r.growth_radius);
  j["volumetric_radius_m"] = num(r.volumetric_radius);
  j["dimensionality"] = {{"linear", r.linear}, {"planar", r.planar},
                         {"volumetric", r.volumetric}, {"invalid", r.invalid}};
  j["fragments_absorbed"] = r.fragments_absorbed;
  // Segments whose convex hull is degenerate (decided before qhull, which runs silently).
  j["segment_hulls"] = {{"tiny", r.hulls_tiny}, {"collinear", r.hulls_collinear},
                        {"flat", r.hulls_flat}, {"solid", r.hulls_solid}};
  j["seconds"] = {{"total", r.seconds_total}, {"normals", r.seconds_normals},
                  {"segmentation", r.seconds_segmentation}, {"search", r.seconds_search},
                  {"features", r.seconds_features}, {"growing", r.seconds_growing},
                  {"merging", r.seconds_merging}, {"absorbing", r.seconds_absorbing}};
  return j;
}

json
evaluationToJson(const ev::SegmentationEvaluation& e)
{
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json j;
  j["method"] = e.method;
  j["seconds"] = e.seconds;
  j["segments"] = e.segments;
  j["points_evaluated"] = e.points_evaluated;
  j["points_unsegmented"] = e.points_unsegmented;
  j["segments_under_min_size"] = e.segments_too_small;
  for (const auto& c : e.classes)
    j["classes"][c.name] = {{"precision", num(c.precision)}, {"recall", num(c.recall)},
                            {"f1", num(c.f1)}, {"tp", c.tp}, {"fp", c.fp}, {"fn", c.fn},
                            {"reference_points", c.reference_points}, {"segments", c.segments}};
  return j;
}

json
objectEvaluationToJson(const ev::ObjectEvaluation& e)
{
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json j;
  j["method"] = e.method;
  j["seconds"] = e.seconds;
  j["segments"] = e.segments;
  if (!e.failure.empty()) {
    j["failure"] = e.failure;
    return j;
  }
  for (const auto& c : e.classes)
    j["classes"][c.name] = {{"precision", num(c.precision)}, {"recall", num(c.recall)},
                            {"f1", num(c.f1)}, {"tp", c.tp}, {"fp", c.fp}, {"fn", c.fn},
                            {"objects", c.objects}, {"recognised", c.recognised},
                            {"large_objects", c.large_objects},
                            {"median_valid_segments", num(c.median_valid_segments)},
                            {"median_largest_share", num(c.median_largest_share)}};
  return j;
}

/// Points far outside the data's dense core (a stray return kilometres away) stretch the
/// extent that the ground grid and the origin are taken from and change the segmentation: said,
/// not hidden. "" when the extent is within 4 × that of the central 99.8 % of the points.
std::string
farOutlierWarning(const pcl::PointCloud<pcl::PointXYZ>& cloud)
{
  if (cloud.size() < 1000)
    return "";
  double core = 0.0, full = 0.0;
  for (int axis = 0; axis < 2; ++axis) {
    std::vector<double> v;
    v.reserve(cloud.size());
    for (const auto& p : cloud)
      v.push_back(axis == 0 ? p.x : p.y);
    const std::vector<double> q = stats::quantiles(std::move(v), {0.0, 0.001, 0.999, 1.0});
    core = std::max(core, q[2] - q[1]);
    full = std::max(full, q[3] - q[0]);
  }
  if (!(full > 4.0 * core))
    return "";
  char buf[240];
  std::snprintf(buf, sizeof(buf),
                "the points span %.0f m, but 99.8 %% of them lie within %.0f m: far outliers change the "
                "grid and the segmentation; crop them first",
                full, core);
  return buf;
}

/// Below about 2 points per m² a house or a crown is a handful of points, and the growth radius
/// (2 k_min-th neighbour distances, about 4 mean spacings 1/√density) spans the gaps between
/// them: objects join. Measured on IGN tiles thinned at
/// random (docs/BENCHMARKS.md, "Sparse data"): said before the run, not discovered in the maps.
std::string
sparseDataWarning(const pcl::PointCloud<pcl::PointXYZ>& cloud, double metres_per_unit)
{
  // Density over the 5 m cells that hold points: gaps (water, a cropped corner) do not count.
  std::vector<Eigen::Vector3d> points;
  points.reserve(cloud.size());
  for (const auto& p : cloud)
    points.emplace_back(p.x, p.y, p.z);
  const double cell = 5.0 / metres_per_unit;
  const auto occupied = static_cast<double>(occupiedCells(points, 0, 1, cell));
  const double cell_m = cell * metres_per_unit;
  const double density = static_cast<double>(cloud.size()) / (occupied * cell_m * cell_m);
  if (!(occupied > 0.0) || density >= 2.0)
    return "";
  const double spacing = 1.0 / std::sqrt(density);
  char buf[400];
  std::snprintf(buf, sizeof(buf),
                "%.3g points per m² (mean spacing %.2f m): too sparse for whole objects; houses, "
                "crowns and the ground closer than about 4 spacings join (on an IGN tile thinned "
                "to 1.5 points per m², vegetation F1 fell from 0.89 to 0.34); object "
                "segmentation wants at least 2-4 points per m²",
                density, spacing);
  return buf;
}

/// Segments and points per class (IMRG), e.g. "building 12 (30.2 %)", and the same as JSON:
/// per class name {segments, points} (objects, or planes with -level planes).
std::string
classSummary(const std::vector<pcl::PointIndices>& segments,
             const std::vector<segmentation::ObjectClass>& classes, std::size_t points, json& j)
{
  std::map<segmentation::ObjectClass, std::pair<std::size_t, std::size_t>> per;
  for (std::size_t s = 0; s < segments.size() && s < classes.size(); ++s) {
    ++per[classes[s]].first;
    per[classes[s]].second += segments[s].indices.size();
  }
  std::string text;
  j = json::object();
  for (const auto& [c, n] : per) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "%s%s %zu (%.1f %%)", text.empty() ? "" : ", ",
                  segmentation::toString(c), n.first,
                  100.0 * static_cast<double>(n.second) / static_cast<double>(std::max<std::size_t>(points, 1)));
    text += buf;
    j[segmentation::toString(c)] = {{"segments", n.first}, {"points", n.second}};
  }
  return text;
}

int
fail(const std::string& msg)
{
  print_error("[pcl_ls3d_segment] %s\n", msg.c_str());
  return EXIT_FAILURE;
}

}  // namespace

int
main(int argc, char** argv)
{
  pcl_ls3d::tools::lineBufferedStdout();
  if (argc < 2 || find_switch(argc, argv, "-h") || find_switch(argc, argv, "--help") ||
      find_switch(argc, argv, "-help")) {
    printHelp(argv[0]);
    return argc < 2 ? EXIT_FAILURE : EXIT_SUCCESS;
  }
  std::string input, error, out_pcd, out_json, class_spec;
  if (!checkArguments(argc, argv, input, error))
    return fail(error);
  ev::SegmentationRunSettings settings;
  if (!parseSettings(argc, argv, settings, error))
    return fail(error);
  parse_argument(argc, argv, "-o", out_pcd);
  parse_argument(argc, argv, "-json", out_json);
  const bool overwrite = find_switch(argc, argv, "-overwrite");
  const bool evaluate = find_switch(argc, argv, "-evaluate");
  ev::SegmentationEvaluationSettings eval_settings;
  double min_size = 0;
  if (!parseNumber(argc, argv, "-eval_min_size", min_size, error))
    return fail(error);
  if (min_size < 0 || min_size != std::floor(min_size))
    return fail("-eval_min_size must be a non-negative integer");
  eval_settings.min_segment_size = static_cast<std::size_t>(min_size);
  double object_radius = -1.0;
  if (!parseNumber(argc, argv, "-object_radius", object_radius, error))
    return fail(error);
  if (object_radius == 0.0 || object_radius > 1e6)
    return fail("-object_radius must be positive (metres), or negative for automatic");
  if (parse_argument(argc, argv, "-classes", class_spec) >= 0 &&
      !ev::parseClassGroups(class_spec, eval_settings.groups, error))
    return fail("-classes: " + error);
  if (!out_pcd.empty() && io::fileExtension(out_pcd) != "pcd")
    return fail("-o must name a .pcd file, got '" + out_pcd + "'");
  if (!out_pcd.empty() && !out_json.empty() && io::isSameFile(out_pcd, out_json))
    return fail("-o and -json name the same file");
  if (!checkOutput(out_pcd, input, overwrite, error) ||
      !checkOutput(out_json, input, overwrite, error))
    return fail(error);

  // ---- load ----------------------------------------------------------------------------
  TicToc tt;
  tt.tic();
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  if (evaluate && ev::isSegmentsFile(input))
    return fail("-evaluate: '" + input + "' is a SEGMENTS file of pcl_ls3d_segment: its labels are segment "
                "ids, not reference classes (evaluate the labelled input instead)");
  if (!io::loadCloud(input, cloud, info, error))
    return fail(error);
  if (cloud.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    return fail("cloud too large for pcl::PointIndices");
  const double t_load = tt.toc() / 1000.0;
  print_info("Loaded %s: %zu points (%zu non-finite dropped), origin (%.3f, %.3f, %.3f) in %.3f s\n",
             input.c_str(), cloud.size(), info.points_dropped_nonfinite, info.origin.x(),
             info.origin.y(), info.origin.z(), t_load);
  // The multi-rule methods' smallest neighbourhood (pcl_rg runs on fewer: its clusters say so).
  const int k_min = settings.k_min > 0 ? settings.k_min : segmentation::NeighbourhoodSettings().k_min;
  if (settings.method != ev::SegmentationMethod::PclRegionGrowing && cloud.size() < static_cast<std::size_t>(k_min))
    return fail("need at least k_min = " + std::to_string(k_min) + " finite points (-k) for " +
                ev::toString(settings.method) + ", got " + std::to_string(cloud.size()));
  if (cloud.size() < 3)
    return fail("need at least 3 finite points, got " + std::to_string(cloud.size()));

  pcl::PointCloud<pcl::PointXYZ>::Ptr xyz(new pcl::PointCloud<pcl::PointXYZ>);
  xyz->resize(cloud.size());
  std::vector<int> reference(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    (*xyz)[i].x = cloud[i].x;
    (*xyz)[i].y = cloud[i].y;
    (*xyz)[i].z = cloud[i].z;
    reference[i] = cloud[i].classification;
  }
  if (evaluate) {
    const ev::ClassLookup lookup(eval_settings.groups, eval_settings.excluded_codes);
    std::size_t labelled = 0;
    for (int c : reference)
      labelled += lookup.groupOf(c) >= 0;
    if (labelled == 0)
      return fail("-evaluate: no point of '" + input + "' carries a label of the evaluated classes");
  }

  // Metres per unit: the LAS CRS's, else the tool's assumption of metres; a CRS without a
  // linear unit (geographic degrees) gives no density to judge.
  const std::string wkt =
      info.format == "las" ? maps::crsFromLasVlrs(info.las.vlrs) : info.file_crs_wkt;
  const double crs_unit = maps::crsLinearUnit(wkt);
  const bool density_known = wkt.empty() || crs_unit > 0.0;
  json warnings = json::array();
  for (const std::string& w :
       {farOutlierWarning(*xyz),
        density_known ? sparseDataWarning(*xyz, crs_unit > 0.0 ? crs_unit : 1.0) : std::string()})
    if (!w.empty()) {
      print_warn("Warning: %s\n", w.c_str());
      warnings.push_back(w);
    }

  // ---- segment (one method, or all four for -evaluate) ----------------------------------
  std::vector<ev::SegmentationMethod> methods{settings.method};
  if (evaluate) {
    methods = {ev::SegmentationMethod::IMRG, ev::SegmentationMethod::MRG,
               ev::SegmentationMethod::PclRegionGrowing, ev::SegmentationMethod::VoxelGrid};
    // The selected method first, so that the voxel grid can match IMRG's count either way.
    std::stable_partition(methods.begin(), methods.end(),
                          [&](ev::SegmentationMethod m) { return m == settings.method; });
  }
  json report;
  report["input"] = input;
  report["points"] = cloud.size();
  report["points_in_file"] = info.points_in_file;
  report["points_dropped_nonfinite"] = info.points_dropped_nonfinite;
  report["origin"] = {info.origin.x(), info.origin.y(), info.origin.z()};
  report["level"] = settings.level == ev::SegmentationLevel::Planes ? "planes" : "objects";
  report["seconds_load"] = t_load;
  report["warnings"] = warnings;
  ev::ReferenceObjects objects;
  if (evaluate) {
    ev::ReferenceObjectSettings ro;
    ro.groups = eval_settings.groups;
    ro.excluded_codes = eval_settings.excluded_codes;
    ro.radius = object_radius;
    tt.tic();
    if (!ev::referenceObjectsFromLabels(*xyz, reference, ro, objects, error))
      return fail("-evaluate: " + error);
    print_info("Reference objects: %zu (connected components per class group, radius %.2f m) "
               "in %.3f s\n", objects.objects(), objects.radius, tt.toc() / 1000.0);
    report["reference_objects"] = {{"objects", objects.objects()}, {"radius_m", objects.radius}};
  }
  std::vector<ev::SegmentationEvaluation> evaluations;
  std::vector<ev::ObjectEvaluation> object_evaluations;
  std::vector<pcl::PointIndices> selected;
  std::vector<segmentation::ObjectClass> selected_classes;
  std::vector<ev::SegmentationEvaluation> class_evaluations;
  std::size_t imrg_segments = 0;
  for (auto m : methods) {
    ev::SegmentationRunSettings s = settings;
    s.method = m;
    s.voxel_segments = imrg_segments;
    ev::SegmentationRun run;
    tt.tic();
    const bool ok = (m != ev::SegmentationMethod::VoxelGrid || imrg_segments > 0)
                        ? ev::runSegmentation(xyz, s, run, error)
                        : (error = "no IMRG segment count to match", false);
    if (!ok) {
      // The selected method's failure ends the run; a baseline's is a row of the tables.
      if (m == settings.method)
        return fail(error);
      print_warn("%s failed: %s\n", ev::toString(m).c_str(), error.c_str());
      json j;
      j["method"] = ev::toString(m);
      j["failure"] = error;
      report["runs"].push_back(j);
      ev::SegmentationEvaluation e;
      e.method = ev::toString(m);
      e.seconds = run.seconds_total;
      e.failure = error;
      evaluations.push_back(e);
      ev::ObjectEvaluation o;
      o.method = e.method;
      o.seconds = e.seconds;
      o.failure = error;
      object_evaluations.push_back(o);
      report["evaluation"].push_back({{"method", e.method}, {"failure", error}});
      report["object_evaluation"].push_back(objectEvaluationToJson(o));
      continue;
    }
    if (m == ev::SegmentationMethod::IMRG)
      imrg_segments = run.segments.size();
    print_info("%s: %zu segments (%zu before merging) in %.3f s", ev::toString(m).c_str(),
               run.segments.size(), run.segments_before_merge, tt.toc() / 1000.0);
    if (m == ev::SegmentationMethod::IMRG || m == ev::SegmentationMethod::MRG)
      print_info("; v_t %.4f m, d_t %.4f m, s_t %.4f m, V_t %.3f; linear/planar/volumetric "
                 "%zu/%zu/%zu\n",
                 run.residual_threshold, run.distance_threshold, run.similarity_threshold,
                 run.volume_threshold, run.linear, run.planar, run.volumetric);
    else if (m == ev::SegmentationMethod::PclRegionGrowing)
      print_info(" (normals %.3f s; %zu points in the rest segment)\n", run.seconds_normals,
                 run.rest_points);
    else
      print_info(" (voxel edge %.3f m)\n", run.voxel_size);
    json rj = runToJson(run);
    if (m == ev::SegmentationMethod::VoxelGrid)
      rj["voxel_size_m"] = run.voxel_size;
    if (m == ev::SegmentationMethod::PclRegionGrowing)
      rj["rest_points"] = run.rest_points;
    report["runs"].push_back(rj);
    if (m == settings.method) {
      selected = run.segments;
      selected_classes = run.classes;
      if (run.rest_points > 0)  // pcl_rg's rest is for the evaluation only: no segment, label 0
        selected.pop_back();
      if (selected.empty())
        print_warn("%s: every point lies in a cluster under the minimum size: all labels 0\n",
                   ev::toString(m).c_str());
    }
    if (!run.classes.empty()) {
      json classes;
      print_info("%s classes: %s\n", ev::toString(m).c_str(),
                 classSummary(run.segments, run.classes, cloud.size(), classes).c_str());
      report["runs"].back()["classes"] = classes;
    }
    if (evaluate) {
      ev::SegmentationEvaluation e;
      e.method = ev::toString(m);
      e.seconds = run.seconds_total;
      if (!ev::evaluateSegmentation(run.segments, reference, eval_settings, e, error))
        return fail(error);
      report["evaluation"].push_back(evaluationToJson(e));
      evaluations.push_back(e);
      ev::ObjectEvaluation o;
      o.method = e.method;
      o.seconds = e.seconds;
      if (!ev::evaluateObjects(run.segments, objects, {}, o, error))
        return fail(error);
      report["object_evaluation"].push_back(objectEvaluationToJson(o));
      object_evaluations.push_back(o);
      if (!run.classes.empty()) {
        ev::SegmentationEvaluation c;
        c.method = e.method + " classes";
        c.seconds = e.seconds;
        c.segments = run.segments.size();
        if (!ev::evaluateClassification(ev::classCodesFromSegments(run.segments, run.classes, cloud.size()),
                                        reference, eval_settings, c, error))
          return fail(error);
        report["class_evaluation"].push_back(evaluationToJson(c));
        class_evaluations.push_back(c);
      }
    }
  }
  if (evaluate) {
    const std::string excluded =
        ev::describeExcludedCodes(eval_settings.groups, eval_settings.excluded_codes);
    print_info("\nObject-based precision / recall / F1 (%%), Wang et al. 2021 sec. 4.1: a segment "
               "is valid for the\nreference object holding more than half of its labelled "
               "points; an object is recognised when\nits valid segments hold more than half of "
               "it; %s.\n%s",
               excluded.c_str(), ev::formatObjectTable(object_evaluations).c_str());
    const ev::ObjectEvaluationSettings object_settings;
    print_info("\nFragmentation: recognised / objects, and over objects of at least %zu points "
               "the median number of\nvalid segments per object and the median share of the "
               "object in its largest valid segment.\n%s",
               object_settings.min_object_points,
               ev::formatFragmentationTable(object_evaluations, object_settings.min_object_points)
                   .c_str());
    print_info("\nPer-point precision / recall / F1 (%%); segments mapped to their majority class;\n"
               "points in no segment%s count as false negatives; %s.\n%s",
               eval_settings.min_segment_size > 0
                   ? (" (or in one under " + std::to_string(eval_settings.min_segment_size) +
                      " points)").c_str()
                   : "",
               excluded.c_str(), ev::formatSegmentationTable(evaluations).c_str());
    for (const auto& e : evaluations)
      if (e.failure.empty())
        print_info("%s confusion:\n%s", e.method.c_str(), ev::describeConfusion(e).c_str());
    if (!class_evaluations.empty())
      print_info("\nObject classes, per point precision / recall / F1 (%%): each point takes the "
                 "class IMRG gave its object\n(no reference label used); unclassified counts as "
                 "no prediction; %s.\n%s%s",
                 excluded.c_str(), ev::formatSegmentationTable(class_evaluations).c_str(),
                 ev::describeConfusion(class_evaluations.front()).c_str());
  }

  // ---- write -----------------------------------------------------------------------------
  if (!out_pcd.empty()) {
    tt.tic();
    ev::InputLayout layout;
    layout.points_in_file = info.points_in_file;
    layout.nonfinite = info.nonfinite_indices;
    layout.origin = info.origin;
    layout.crs_wkt = wkt;
    std::vector<std::uint8_t> codes;
    for (const auto c : selected_classes)
      codes.push_back(segmentation::lasCode(c));
    if (!ev::saveSegmentsPcd(out_pcd, *xyz, selected, layout, error, codes))
      return fail(error);
    const double t_write = tt.toc() / 1000.0;
    report["seconds_write"] = t_write;
    report["segments_file"] = {{"path", out_pcd},
                               {"points", std::max(info.points_in_file, cloud.size())},
                               {"coordinates", "float32, local: file coordinate = x + origin"},
                               {"origin", {info.origin.x(), info.origin.y(), info.origin.z()}},
                               {"label", "segment id + 1; 0 = no segment or non-finite input"},
                               {"crs", wkt.empty() ? json(nullptr) : json(maps::crsName(wkt))}};
    if (!codes.empty()) {
      report["segments_file"]["classification"] =
          "LAS code of the segment's object class: " + segmentation::describeLasCodes() +
          "; 0 = no segment";
      json names = json::array();
      for (const auto c : selected_classes)
        names.push_back(segmentation::toString(c));
      report["segment_classes"] = names;  // index = label - 1
    }
    print_info("Wrote %s (%zu points in input order, %zu segments; local float coordinates, "
               "origin (%.3f, %.3f, %.3f) in its header) in %.3f s\n",
               out_pcd.c_str(), std::max(info.points_in_file, cloud.size()), selected.size(),
               info.origin.x(), info.origin.y(), info.origin.z(), t_write);
  }
  if (!out_json.empty()) {
    if (!tools::writeJsonFile(out_json, report))
      return fail("cannot write '" + out_json + "'");
    print_info("Wrote %s\n", out_json.c_str());
  }
  return EXIT_SUCCESS;
}
