/// \file pcl_ls3d_segment.cpp
/// \brief Multi-factor segmentation of a point cloud (IMRG, MRG or PCL region growing), with an
///        optional evaluation of all three against the reference labels of the input.
///
/// Output SEGMENTS.pcd (segments_file.h): every input point in input order, x y z float in the
/// local frame (origin in a "# pcl_ls3d origin" header line and the JSON report), label =
/// segment id + 1 (0 = in no segment, and every non-finite input point), rgba per segment, so
/// that pcl::io::loadPCDFile into pcl::PointXYZRGBL reads it.

#include "segment_report.h"
#include "segment_warnings.h"
#include "tool_options.h"
#include "tool_output.h"

#include <pcl_ls3d/evaluation/object_metrics.h>
#include <pcl_ls3d/evaluation/reference_objects.h>
#include <pcl_ls3d/evaluation/segmentation_classes.h>
#include <pcl_ls3d/evaluation/segmentation_metrics.h>
#include <pcl_ls3d/evaluation/segmentation_report.h>
#include <pcl_ls3d/evaluation/segmentation_runner.h>
#include <pcl_ls3d/evaluation/segments_file.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/json_text.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/segmentation/dimensionality_features.h>
#include <pcl_ls3d/segmentation/object_classes.h>

#include <pcl/common/time.h>
#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>
#include <pcl/io/pcd_io.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

using namespace pcl::console;
using namespace pcl_ls3d;
using nlohmann::json;
namespace ev = pcl_ls3d::evaluation;

namespace {

const std::set<std::string> kValueOptions{"-o",
                                          "-mode",
                                          "-json",
                                          "-k",
                                          "-Nt",
                                          "-Mt",
                                          "-vt",
                                          "-dt",
                                          "-st",
                                          "-Vt",
                                          "-classes",
                                          "-threads",
                                          "-eval_min_size",
                                          "-min_fragment",
                                          "-level",
                                          "-object_radius"};
const std::set<std::string> kFlagOptions{"-evaluate", "-overwrite", "-h", "--help", "-help"};

void
printHelp(const char* prog)
{
  print_info("Multi-factor segmentation by improved multi-rule region growing (Wang et al. 2021).\n\n"
             "Syntax: %s INPUT [options]\n"
             "  INPUT              .las .laz .copc.laz .pcd .ply .xyz/.txt (LAS classification / PCD label = "
             "reference;\n"
             "                     its numbers of returns, where recorded, tell parked cars from shrubs;\n"
             "                     a CRS in feet is segmented in metres: lengths, thresholds and\n"
             "                     the options below are metres, SEGMENTS.pcd keeps the file's unit;\n"
             "                     one in degrees is refused)\n"
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

/// Strict number (tool_options.h): the whole string must parse and be finite.
bool
parseNumber(int argc, char** argv, const char* name, double& value, std::string& error)
{
  return tools::numberOption(argc, argv, name, value, error);
}

/// -mode and -level.
bool
methodOptions(int argc, char** argv, ev::SegmentationRunSettings& s, std::string& error)
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
  return true;
}

/// -k kmin,kmax: the neighbourhood range.
bool
neighbourhoodOption(int argc, char** argv, ev::SegmentationRunSettings& s, std::string& error)
{
  std::string k;
  if (parse_argument(argc, argv, "-k", k) < 0)
    return true;
  char *e1 = nullptr, *e2 = nullptr;
  const long a = std::strtol(k.c_str(), &e1, 10);
  const long b = (*e1 == ',') ? std::strtol(e1 + 1, &e2, 10) : 0;
  if (*e1 != ',' || !e2 || *e2 != '\0' || a < 3 || b < a || b > 65535) {
    error = "-k expects kmin,kmax with 3 <= kmin <= kmax, got '" + k + "'";
    return false;
  }
  s.k_min = static_cast<int>(a);
  s.k_max = static_cast<int>(b);
  return true;
}

/// The thresholds, -threads and -min_fragment, each in its range.
bool
numericOptions(int argc, char** argv, ev::SegmentationRunSettings& s, std::string& error)
{
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
  return true;
}

bool
parseSettings(int argc, char** argv, ev::SegmentationRunSettings& s, std::string& error)
{
  if (!methodOptions(argc, argv, s, error) || !neighbourhoodOption(argc, argv, s, error) ||
      !numericOptions(argc, argv, s, error))
    return false;
  if (s.method == ev::SegmentationMethod::PclRegionGrowing && tools::optionValue(argc, argv, "-level")) {
    error = "-level applies to imrg and mrg, not to -mode pcl_rg";
    return false;
  }
  return s.isValid(&error);
}

/// Refuses an output equal to the input, an existing one without -overwrite, or one that cannot
/// be written (tool_options.h), before any work.
bool
checkOutput(const std::string& out, const std::string& input, bool overwrite, std::string& error)
{
  return tools::checkOutputFile(out, {input}, overwrite, error);
}

int
fail(const std::string& msg)
{
  print_error("[pcl_ls3d_segment] %s\n", msg.c_str());
  return EXIT_FAILURE;
}

/// Everything the command line asks for, checked before any input is read.
struct Options
{
  std::string input, out_pcd, out_json;
  bool overwrite = false, evaluate = false;
  ev::SegmentationRunSettings settings;
  ev::SegmentationEvaluationSettings eval;
  double object_radius = -1.0;  ///< reference objects; negative: automatic
};

bool
parseOptions(int argc, char** argv, Options& o, std::string& error)
{
  if (!checkArguments(argc, argv, o.input, error) || !parseSettings(argc, argv, o.settings, error))
    return false;
  parse_argument(argc, argv, "-o", o.out_pcd);
  parse_argument(argc, argv, "-json", o.out_json);
  o.overwrite = find_switch(argc, argv, "-overwrite");
  o.evaluate = find_switch(argc, argv, "-evaluate");
  double min_size = 0;
  if (!parseNumber(argc, argv, "-eval_min_size", min_size, error))
    return false;
  if (min_size < 0 || min_size != std::floor(min_size))
    return (error = "-eval_min_size must be a non-negative integer"), false;
  o.eval.min_segment_size = static_cast<std::size_t>(min_size);
  if (!parseNumber(argc, argv, "-object_radius", o.object_radius, error))
    return false;
  if (o.object_radius == 0.0 || o.object_radius > 1e6)
    return (error = "-object_radius must be positive (metres), or negative for automatic"), false;
  std::string class_spec;
  if (parse_argument(argc, argv, "-classes", class_spec) >= 0 &&
      !ev::parseClassGroups(class_spec, o.eval.groups, error))
    return (error = "-classes: " + error), false;
  if (!o.out_pcd.empty() && io::fileExtension(o.out_pcd) != "pcd")
    return (error = "-o must name a .pcd file, got '" + o.out_pcd + "'"), false;
  if (!o.out_pcd.empty() && !o.out_json.empty() && io::isSameFile(o.out_pcd, o.out_json))
    return (error = "-o and -json name the same file"), false;
  return checkOutput(o.out_pcd, o.input, o.overwrite, error) &&
         checkOutput(o.out_json, o.input, o.overwrite, error);
}

/// The input as the methods see it: finite points, local coordinates, reference labels.
struct Input
{
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  pcl::PointCloud<pcl::PointXYZ>::Ptr xyz{new pcl::PointCloud<pcl::PointXYZ>};
  /// What the methods segment: xyz in metres (the classes' heights and sizes are physical);
  /// xyz itself unless the CRS declares another unit.
  pcl::PointCloud<pcl::PointXYZ>::Ptr metric = xyz;
  /// Metres per unit in plan and in height, as the CRS declares them; 0: not declared (metres
  /// assumed).
  double metres_per_unit = 0.0, metres_per_height_unit = 0.0;
  std::vector<int> reference;          ///< LAS classification / PCD label per point
  std::vector<std::uint8_t> returns;   ///< number of returns per point (all 1 where not recorded)
  double multiple_return_share = 0.0;  ///< of the points; 0: returns not recorded
  std::string wkt;                     ///< CRS of the coordinates; empty: none declared
  double seconds = 0.0;
};

/// Share of the points from pulses with several returns; 0 when the file records none (all 1).
double
multipleReturnShare(const std::vector<std::uint8_t>& returns)
{
  const auto multiple = std::count_if(returns.begin(), returns.end(), [](std::uint8_t r) { return r > 1; });
  return returns.empty() ? 0.0 : static_cast<double>(multiple) / static_cast<double>(returns.size());
}

/// One line on the returns, where IMRG's classes use them (a share above 0: recorded, as
/// segmentation::recordsReturns says).
void
printReturns(const Options& o, double multiple_return_share)
{
  if (o.settings.method != ev::SegmentationMethod::IMRG && !o.evaluate)
    return;
  if (multiple_return_share > 0.0)
    print_info("Returns recorded: %.1f %% of the points from pulses with several returns (IMRG's "
               "classes use them to tell parked cars from shrubs)\n",
               100.0 * multiple_return_share);
  else
    print_info("No returns recorded (one per pulse): IMRG names car-sized rough objects "
               "vegetation\n");
}

/// The units the CRS declares: a compound CRS whose height unit GDAL does not show is taken
/// to use its plan unit, and said so.
void
readUnits(Input& in)
{
  in.metres_per_unit = maps::crsLinearUnit(in.wkt);
  in.metres_per_height_unit = maps::crsVerticalUnit(in.wkt);
  if (in.metres_per_unit > 0.0 && !(in.metres_per_height_unit > 0.0)) {
    print_warn("Warning: the CRS's height unit is not readable; heights taken in its plan unit\n");
    in.metres_per_height_unit = in.metres_per_unit;
  }
}

/// The methods' cloud in metres: a projected CRS in feet (US State Plane, Oregon Lambert)
/// would otherwise see its 2 m building height as 0.6 m and a car as 1.4 m long.
void
toMetres(Input& in)
{
  const double xy = in.metres_per_unit, z = in.metres_per_height_unit;
  if (!(xy > 0.0) || (xy == 1.0 && z == 1.0))
    return;
  in.metric.reset(new pcl::PointCloud<pcl::PointXYZ>(*in.xyz));
  for (auto& p : *in.metric) {
    p.x = static_cast<float>(p.x * xy);
    p.y = static_cast<float>(p.y * xy);
    p.z = static_cast<float>(p.z * z);
  }
  print_info("Coordinates in %s (%.7g m, heights %.7g m per unit): segmented in metres; the "
             "lengths below are metres, SEGMENTS.pcd keeps the file's unit\n",
             maps::crsLinearUnitName(in.wkt).c_str(), xy, z);
}

bool
loadInput(const Options& o, Input& in, std::string& error)
{
  TicToc tt;
  tt.tic();
  if (!io::loadCloud(o.input, in.cloud, in.info, error))
    return false;
  if (o.evaluate && in.info.segments_file)  // the reader recognised it (io::kPcdSegmentsMarker)
    return (error = "-evaluate: '" + o.input +
                    "' is a SEGMENTS file of pcl_ls3d_segment: its labels "
                    "are segment ids, not reference classes (evaluate the labelled input instead)"),
           false;
  const std::size_t n = in.cloud.size();
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    return (error = "cloud too large for pcl::PointIndices"), false;
  in.seconds = tt.toc() / 1000.0;
  print_info("Loaded %s: %zu points (%zu non-finite dropped), origin (%.3f, %.3f, %.3f) in %.3f s\n",
             o.input.c_str(), n, in.info.points_dropped_nonfinite, in.info.origin.x(), in.info.origin.y(),
             in.info.origin.z(), in.seconds);
  // The multi-rule methods' smallest neighbourhood (pcl_rg runs on fewer: its clusters say so).
  const int k_min = o.settings.k_min > 0 ? o.settings.k_min : segmentation::NeighbourhoodSettings().k_min;
  if (o.settings.method != ev::SegmentationMethod::PclRegionGrowing && n < static_cast<std::size_t>(k_min))
    return (error = "need at least k_min = " + std::to_string(k_min) + " finite points (-k) for " +
                    ev::toString(o.settings.method) + ", got " + std::to_string(n)),
           false;
  if (n < 3)
    return (error = "need at least 3 finite points, got " + std::to_string(n)), false;
  in.xyz->resize(n);
  in.reference.resize(n);
  in.returns.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    (*in.xyz)[i] = pcl::PointXYZ(in.cloud[i].x, in.cloud[i].y, in.cloud[i].z);
    in.reference[i] = in.cloud[i].classification;
    in.returns[i] = in.cloud[i].number_of_returns;
  }
  const ev::ClassLookup lookup(o.eval.groups, o.eval.excluded_codes);
  if (o.evaluate &&
      std::none_of(in.reference.begin(), in.reference.end(), [&](int c) { return lookup.groupOf(c) >= 0; }))
    return (error = "-evaluate: no point of '" + o.input + "' carries a label of the evaluated classes"),
           false;
  in.wkt = maps::crsOfFile(in.info);
  if (!(error = maps::notInLengths(o.input, in.wkt)).empty())
    return false;
  readUnits(in);
  toMetres(in);
  in.multiple_return_share = multipleReturnShare(in.returns);
  printReturns(o, in.multiple_return_share);
  return true;
}

/// Far outliers and sparse data, said before the run (printed, and returned for the JSON).
json
inputWarnings(const Input& in)
{
  // Metres are assumed without a CRS; a CRS whose unit is unreadable gives no density to judge.
  const bool density_known = in.wkt.empty() || in.metres_per_unit > 0.0;
  json warnings = json::array();
  for (const std::string& w : {tools::farOutlierWarning(*in.metric),
                               density_known ? tools::sparseDataWarning(*in.metric) : std::string()})
    if (!w.empty()) {
      print_warn("Warning: %s\n", w.c_str());
      warnings.push_back(w);
    }
  return warnings;
}

/// What the runs gave: the selected method's segments and classes, and the evaluation rows.
struct Results
{
  std::vector<pcl::PointIndices> selected;
  std::vector<segmentation::ObjectClass> selected_classes;
  std::vector<ev::SegmentationEvaluation> evaluations, class_evaluations;
  std::vector<ev::ObjectEvaluation> object_evaluations;
};

/// A baseline that failed: a row of every table, with its reason.
void
recordFailure(ev::SegmentationMethod m, double seconds, const std::string& why, json& report, Results& r)
{
  print_warn("%s failed: %s\n", ev::toString(m).c_str(), why.c_str());
  report["runs"].push_back({{"method", ev::toString(m)}, {"failure", why}});
  ev::SegmentationEvaluation e;
  e.method = ev::toString(m);
  e.seconds = seconds;
  e.failure = why;
  r.evaluations.push_back(e);
  ev::ObjectEvaluation o;
  o.method = e.method;
  o.seconds = seconds;
  o.failure = why;
  r.object_evaluations.push_back(o);
  report["evaluation"].push_back({{"method", e.method}, {"failure", why}});
  report["object_evaluation"].push_back(tools::segment_report::objectEvaluationToJson(o));
}

/// One line per run: segments, time, thresholds or the baseline's own figures; and its classes.
void
printRun(ev::SegmentationMethod m, const ev::SegmentationRun& run, double seconds, std::size_t points,
         json& report)
{
  print_info("%s: %zu segments (%zu before merging) in %.3f s", ev::toString(m).c_str(), run.segments.size(),
             run.segments_before_merge, seconds);
  if (m == ev::SegmentationMethod::IMRG || m == ev::SegmentationMethod::MRG)
    print_info("; v_t %.4f m, d_t %.4f m, s_t %.4f m, V_t %.3f; linear/planar/volumetric "
               "%zu/%zu/%zu\n",
               run.residual_threshold, run.distance_threshold, run.similarity_threshold, run.volume_threshold,
               run.linear, run.planar, run.volumetric);
  else if (m == ev::SegmentationMethod::PclRegionGrowing)
    print_info(" (normals %.3f s; %zu points in the rest segment)\n", run.seconds_normals, run.rest_points);
  else
    print_info(" (voxel edge %.3f m)\n", run.voxel_size);
  json rj = tools::segment_report::runToJson(run);
  if (m == ev::SegmentationMethod::VoxelGrid)
    rj["voxel_size_m"] = run.voxel_size;
  if (m == ev::SegmentationMethod::PclRegionGrowing)
    rj["rest_points"] = run.rest_points;
  if (!run.classes.empty()) {
    json classes;
    print_info("%s classes: %s\n", ev::toString(m).c_str(),
               tools::segment_report::classSummary(run.segments, run.classes, points, classes).c_str());
    rj["classes"] = classes;
  }
  report["runs"].push_back(rj);
}

/// The run scored against the reference: per point, per object, and IMRG's classes.
bool
evaluateRun(const Options& o, const Input& in, const ev::ReferenceObjects& objects, ev::SegmentationMethod m,
            const ev::SegmentationRun& run, json& report, Results& r, std::string& error)
{
  ev::SegmentationEvaluation e;
  e.method = ev::toString(m);
  e.seconds = run.seconds_total;
  if (!ev::evaluateSegmentation(run.segments, in.reference, o.eval, e, error))
    return false;
  report["evaluation"].push_back(tools::segment_report::evaluationToJson(e));
  r.evaluations.push_back(e);
  ev::ObjectEvaluation oe;
  oe.method = e.method;
  oe.seconds = e.seconds;
  if (!ev::evaluateObjects(run.segments, objects, {}, oe, error))
    return false;
  report["object_evaluation"].push_back(tools::segment_report::objectEvaluationToJson(oe));
  r.object_evaluations.push_back(oe);
  if (run.classes.empty())
    return true;
  ev::SegmentationEvaluation c;
  if (!ev::evaluateRunClasses(run, in.reference, o.eval, c, error))
    return false;
  report["class_evaluation"].push_back(tools::segment_report::evaluationToJson(c));
  r.class_evaluations.push_back(c);
  return true;
}

/// The selected method, or all four for -evaluate (the selected one first, so that the voxel
/// grid can match IMRG's count either way). A baseline's failure is a row, not the run's.
bool
runMethods(const Options& o, const Input& in, const ev::ReferenceObjects& objects, json& report, Results& r,
           std::string& error)
{
  std::vector<ev::SegmentationMethod> methods{o.settings.method};
  if (o.evaluate) {
    methods = {ev::SegmentationMethod::IMRG, ev::SegmentationMethod::MRG,
               ev::SegmentationMethod::PclRegionGrowing, ev::SegmentationMethod::VoxelGrid};
    std::stable_partition(methods.begin(), methods.end(),
                          [&](ev::SegmentationMethod m) { return m == o.settings.method; });
  }
  std::size_t imrg_segments = 0;
  for (const auto m : methods) {
    ev::SegmentationRunSettings s = o.settings;
    s.method = m;
    s.voxel_segments = imrg_segments;
    ev::SegmentationRun run;
    TicToc tt;
    tt.tic();
    const bool ok = (m != ev::SegmentationMethod::VoxelGrid || imrg_segments > 0)
                        ? ev::runSegmentation(in.metric, s, run, error, in.returns)
                        : (error = "no IMRG segment count to match", false);
    if (!ok && m == o.settings.method)
      return false;
    if (!ok) {
      recordFailure(m, run.seconds_total, error, report, r);
      continue;
    }
    if (m == ev::SegmentationMethod::IMRG)
      imrg_segments = run.segments.size();
    printRun(m, run, tt.toc() / 1000.0, in.cloud.size(), report);
    if (m == o.settings.method) {
      r.selected = run.segments;
      r.selected_classes = run.classes;
      if (run.rest_points > 0)  // pcl_rg's rest is for the evaluation only: no segment, label 0
        r.selected.pop_back();
      if (r.selected.empty())
        print_warn("%s: every point lies in a cluster under the minimum size: all labels 0\n",
                   ev::toString(m).c_str());
      const std::string dominant = tools::dominantSegmentWarning(run.segments, run.classes, in.cloud.size());
      if (!dominant.empty()) {
        print_warn("Warning: %s\n", dominant.c_str());
        report["warnings"].push_back(dominant);
      }
    }
    if (o.evaluate && !evaluateRun(o, in, objects, m, run, report, r, error))
      return false;
  }
  return true;
}

/// The tables of -evaluate: objects, fragmentation, per point (with confusions), classes.
void
printEvaluation(const Options& o, const Results& r)
{
  const std::string excluded = ev::describeExcludedCodes(o.eval.groups, o.eval.excluded_codes);
  print_info("\nObject-based precision / recall / F1 (%%), Wang et al. 2021 sec. 4.1: a segment "
             "is valid for the\nreference object holding more than half of its labelled "
             "points; an object is recognised when\nits valid segments hold more than half of "
             "it; %s.\n%s",
             excluded.c_str(), ev::formatObjectTable(r.object_evaluations).c_str());
  const ev::ObjectEvaluationSettings object_settings;
  print_info("\nFragmentation: recognised / objects, and over objects of at least %zu points "
             "the median number of\nvalid segments per object and the median share of the "
             "object in its largest valid segment.\n%s",
             object_settings.min_object_points,
             ev::formatFragmentationTable(r.object_evaluations, object_settings.min_object_points).c_str());
  const std::string small = o.eval.min_segment_size > 0
                                ? " (or in one under " + std::to_string(o.eval.min_segment_size) + " points)"
                                : "";
  print_info("\nPer-point precision / recall / F1 (%%); segments mapped to their majority class;\n"
             "points in no segment%s count as false negatives; %s.\n%s",
             small.c_str(), excluded.c_str(), ev::formatSegmentationTable(r.evaluations).c_str());
  for (const auto& e : r.evaluations)
    if (e.failure.empty())
      print_info("%s confusion:\n%s", e.method.c_str(), ev::describeConfusion(e).c_str());
  if (!r.class_evaluations.empty())
    print_info("\nObject classes, per point precision / recall / F1 (%%): each point takes the "
               "class IMRG gave its object\n(no reference label used); unclassified counts as "
               "no prediction; %s.\n%s%s",
               excluded.c_str(), ev::formatSegmentationTable(r.class_evaluations).c_str(),
               ev::describeConfusion(r.class_evaluations.front()).c_str());
}

/// SEGMENTS.pcd (segments_file.h) and what the JSON says about it.
bool
writeSegments(const Options& o, const Input& in, const Results& r, json& report, std::string& error)
{
  TicToc tt;
  tt.tic();
  ev::InputLayout layout;
  layout.points_in_file = in.info.points_in_file;
  layout.nonfinite = in.info.nonfinite_indices;
  layout.origin = in.info.origin;
  layout.crs_wkt = in.wkt;
  std::vector<std::uint8_t> codes;
  for (const auto c : r.selected_classes)
    codes.push_back(segmentation::lasCode(c));
  if (!ev::saveSegmentsPcd(o.out_pcd, *in.xyz, r.selected, layout, error, codes))
    return false;
  const double seconds = tt.toc() / 1000.0;
  const std::size_t points = std::max(in.info.points_in_file, in.cloud.size());
  const Eigen::Vector3d& origin = in.info.origin;
  report["seconds_write"] = seconds;
  report["segments_file"] = {{"path", o.out_pcd},
                             {"points", points},
                             {"coordinates", "float32, local: file coordinate = x + origin"},
                             {"origin", {origin.x(), origin.y(), origin.z()}},
                             {"label", "segment id + 1; 0 = no segment or non-finite input"},
                             {"crs", in.wkt.empty() ? json(nullptr) : json(maps::crsName(in.wkt))}};
  if (!codes.empty()) {
    report["segments_file"]["classification"] =
        "LAS code of the segment's object class: " + segmentation::describeLasCodes() + "; 0 = no segment";
    json names = json::array();
    for (const auto c : r.selected_classes)
      names.push_back(segmentation::toString(c));
    report["segment_classes"] = names;  // index = label - 1
  }
  print_info("Wrote %s (%zu points in input order, %zu segments; local float coordinates, "
             "origin (%.3f, %.3f, %.3f) in its header) in %.3f s\n",
             o.out_pcd.c_str(), points, r.selected.size(), origin.x(), origin.y(), origin.z(), seconds);
  return true;
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
  Options o;
  Input in;
  std::string error;
  if (!parseOptions(argc, argv, o, error) || !loadInput(o, in, error))
    return fail(error);

  json report;
  report["input"] = o.input;
  report["points"] = in.cloud.size();
  report["points_in_file"] = in.info.points_in_file;
  report["points_dropped_nonfinite"] = in.info.points_dropped_nonfinite;
  report["origin"] = {in.info.origin.x(), in.info.origin.y(), in.info.origin.z()};
  // Thresholds, spacings and radii in the report are metres; coordinates the file's unit
  // (null: no unit declared, metres assumed).
  report["metres_per_unit"] = in.metres_per_unit > 0.0 ? json{{"horizontal", in.metres_per_unit},
                                                              {"vertical", in.metres_per_height_unit}}
                                                       : json(nullptr);
  report["level"] = o.settings.level == ev::SegmentationLevel::Planes ? "planes" : "objects";
  report["seconds_load"] = in.seconds;
  report["warnings"] = inputWarnings(in);
  report["multiple_return_share"] = in.multiple_return_share;  // 0: returns not recorded

  ev::ReferenceObjects objects;
  if (o.evaluate) {
    ev::ReferenceObjectSettings ro;
    ro.groups = o.eval.groups;
    ro.excluded_codes = o.eval.excluded_codes;
    ro.radius = o.object_radius;
    TicToc tt;
    tt.tic();
    if (!ev::referenceObjectsFromLabels(*in.metric, in.reference, ro, objects, error))
      return fail("-evaluate: " + error);
    print_info("Reference objects: %zu (connected components per class group, radius %.2f m) "
               "in %.3f s\n",
               objects.objects(), objects.radius, tt.toc() / 1000.0);
    report["reference_objects"] = {{"objects", objects.objects()}, {"radius_m", objects.radius}};
  }
  Results results;
  if (!runMethods(o, in, objects, report, results, error))
    return fail(error);
  if (o.evaluate)
    printEvaluation(o, results);
  if (!o.out_pcd.empty() && !writeSegments(o, in, results, report, error))
    return fail(error);
  if (!o.out_json.empty()) {
    if (!tools::writeJsonFile(o.out_json, report))
      return fail("cannot write '" + o.out_json + "'");
    print_info("Wrote %s\n", o.out_json.c_str());
  }
  return EXIT_SUCCESS;
}
