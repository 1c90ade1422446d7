// pcl_ls3d_register: least-squares 3-D surface matching of SOURCE onto TARGET (Zuo et al. 2012).
#include "tool_options.h"
#include "tool_output.h"

#include <pcl_ls3d/adjustment/report_json.h>
#include <pcl_ls3d/evaluation/transform_error.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/cloud_pair.h>
#include <pcl_ls3d/io/json_text.h>
#include <pcl_ls3d/io/las_rewrite.h>
#include <pcl_ls3d/io/strip_tools.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/registration/least_squares_surface_matching.h>

#include <pcl/common/transforms.h>
#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl::console;
using Cloud = pcl::PointCloud<pcl_ls3d::PointLiDAR>;
using LS3D = pcl_ls3d::LeastSquaresSurfaceMatching<pcl_ls3d::PointLiDAR, pcl_ls3d::PointLiDAR>;

namespace {

void
printHelp(const char* prog)
{
  print_info(
      "Least-squares 3D surface matching (LS3D): estimates the similarity transform that maps\n"
      "SOURCE onto TARGET.\n\n"
      "Usage: %s SOURCE TARGET [options]\n"
      "  SOURCE, TARGET       .las .laz .copc.laz .pcd .ply .xyz/.txt (target loaded first;\n"
      "                       the source uses the target's local origin)\n"
      "  -classes C1,C2       match on these LAS classes only (e.g. 2,6: ground and buildings,\n"
      "                       the stable surfaces of airborne strips; vegetation seen from two\n"
      "                       flight lines biases the shift); -o still moves every point\n"
      "  -o ALIGNED           write the transformed source (input coordinates); a LAS or LAZ\n"
      "                       source written as .las or .laz keeps its version, point format, VLRs (CRS)\n"
      "                       and every attribute: only X, Y, Z and the bounds change;\n"
      "                       other outputs declare the target's CRS (else the source's):\n"
      "                       a PCD or PLY in its header, a LAS as a WKT VLR. Heights in\n"
      "                       another unit than the plan (a compound CRS, metres + US feet)\n"
      "                       are matched in the plan unit; outputs keep the files' units\n"
      "  -rule lnd|lzd|icp    conjugate-point rule (default lnd)\n"
      "  -params 7|6|3|1      similarity, rigid (m fixed), translation, height only (default 6)\n"
      "  -fix tx,ty,...       also fix these parameters (tx ty tz phi omega kappa m)\n"
      "  -max_iter N          iteration limit (default 30)\n"
      "  -K k                 reject residuals beyond k*sigma0 (Zuo eq. 15; default 6)\n"
      "  -thin step           use one source point per voxel of this edge (default 0 = all)\n"
      "  -max_dist d          maximum correspondence distance (default unlimited); a finite\n"
      "                       value also skips source points with no target point within it\n"
      "                       before any neighbour search (faster on partial overlap)\n"
      "  -guess d             how far the initial guess may be off: residuals up to d are\n"
      "                       kept in the first iteration, halving each iteration (default\n"
      "                       1 %% of the source extent, at most -max_dist)\n"
      "  -json REPORT         write a JSON report\n"
      "  -truth TRUTH.json    compare with a known transform (key \"transformation\": 4x4\n"
      "                       row-major, SOURCE -> TARGET, input coordinates)\n"
      "  -overwrite           allow replacing existing output files\n"
      "  -h                   this help\n\n"
      "Exit status: 0 a trusted estimate; 1 bad input or options, or no estimate (the -json\n"
      "report says why); 3 an estimate the quality gate refused (UNRELIABLE, STALLED,\n"
      "IMPLAUSIBLE_SCALE: in the report and -json, not written to -o).\n",
      prog);
}

bool
fail(const std::string& message)
{
  print_error("%s\n", message.c_str());
  return false;
}

bool
parseFixList(const std::string& text, std::vector<int>& indices)
{
  std::stringstream ss(text);
  std::string item;
  const auto& names = pcl_ls3d::similarityParameterNames();
  while (std::getline(ss, item, ',')) {
    int found = -1;
    for (int i = 0; i < 7; ++i)
      if (names[static_cast<std::size_t>(i)] == item)
        found = i;
    if (found < 0)
      return false;
    indices.push_back(found);
  }
  return !indices.empty();
}

bool
readTruth(const std::string& path, Eigen::Matrix4d& T, std::string& error)
{
  std::ifstream in(path);
  if (!in)
    return (error = "cannot open truth file " + path).empty();
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    const auto& rows = j.at("transformation");
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        T(r, c) = rows.at(static_cast<std::size_t>(r)).at(static_cast<std::size_t>(c)).get<double>();
  } catch (const std::exception& e) {
    error = "invalid truth file " + path + ": " + e.what();
    return false;
  }
  if (!T.allFinite())
    return (error = "truth transformation in " + path + " is not finite").empty();
  return true;
}

/// Keeps the points of `classes` (all when empty); false when none is left.
bool
keepClasses(Cloud::Ptr& cloud, const std::set<std::uint8_t>& classes, const std::string& path,
            std::string& error)
{
  if (classes.empty())
    return true;
  const pcl::Indices kept = pcl_ls3d::io::filterByClassification(*cloud, classes, true);
  if (kept.empty()) {
    error = path + ": no point of the -classes given";
    return false;
  }
  Cloud::Ptr selected(new Cloud(*cloud, kept));
  cloud = selected;
  return true;
}

/// A LAS source written as LAS keeps what a surveyor relies on: the header's version and point
/// format, every VLR (the CRS) and every record byte but X, Y, Z (io::rewriteLas); all records,
/// in file order, moved by T (input coordinates).
bool
writeMovedLas(const std::string& source_path, const Eigen::Matrix4d& T, const std::string& out_path,
              bool overwrite, std::string& error)
{
  pcl_ls3d::io::LasRecordFile las;
  if (!las.open(source_path, error))
    return false;
  pcl_ls3d::io::LasRewriteSummary summary;
  const auto move = [&T](std::size_t, Eigen::Vector3d& x) {
    x = (T * x.homogeneous()).head<3>();
    return true;
  };
  return pcl_ls3d::io::rewriteLas(las, nullptr, move, out_path, summary, error, overwrite);
}

/// Everything the command line asks for, checked before any input is read.
struct Options
{
  std::string source_path, target_path, out_path, json_path, truth_path;
  std::string rule_text = "lnd", classes_text;
  bool overwrite = false;
  std::set<std::uint8_t> classes;  ///< -classes; empty: every point
  pcl_ls3d::ConjugateRuleType rule = pcl_ls3d::ConjugateRuleType::LND;
  pcl_ls3d::AdjustmentSettings settings;
  double K = 6.0;  ///< Zuo's weight-function constant
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity();
};

/// -params, -fix, -max_iter, -thin, -max_dist, -guess and -rule into the adjustment settings.
bool
parseSettings(int argc, char** argv, Options& o, std::string& why)
{
  std::string fix_text;
  int max_iter = 30;
  double thin = 0.0, max_dist = -1.0, guess = 0.0;
  parse_argument(argc, argv, "-rule", o.rule_text);
  parse_argument(argc, argv, "-fix", fix_text);
  using pcl_ls3d::tools::integerOption;
  using pcl_ls3d::tools::numberOption;
  pcl_ls3d::ParameterModel model = pcl_ls3d::ParameterModel::RIGID_6;
  if (!pcl_ls3d::tools::parameterModelOption(argc, argv, {"7", "6", "3", "1"}, model, why) ||
      !integerOption(argc, argv, "-max_iter", max_iter, why, 1, 1000000) ||
      !numberOption(argc, argv, "-K", o.K, why) || !numberOption(argc, argv, "-thin", thin, why) ||
      !numberOption(argc, argv, "-max_dist", max_dist, why) ||
      !numberOption(argc, argv, "-guess", guess, why))
    return false;
  // No sentinel values: a given distance is a distance.
  const bool max_dist_given = pcl_ls3d::tools::optionValue(argc, argv, "-max_dist") != nullptr;
  const bool guess_given = pcl_ls3d::tools::optionValue(argc, argv, "-guess") != nullptr;
  if (max_dist_given && !(max_dist > 0.0))
    return (why = "-max_dist must be > 0 (leave it out for no limit)"), false;
  if (guess_given && !(guess > 0.0))
    return (why = "-guess must be > 0 (leave it out for the default, 1 % of the source extent)"), false;
  if (!pcl_ls3d::parseConjugateRuleType(o.rule_text, o.rule))
    return (why = "unknown -rule " + o.rule_text + " (lnd, lzd or icp)"), false;
  pcl_ls3d::AdjustmentSettings& settings = o.settings;
  settings.setParameterModel(model);
  std::vector<int> fixes;
  if (pcl_ls3d::tools::optionValue(argc, argv, "-fix") && fix_text.empty())
    return (why = "-fix needs a comma list of tx,ty,tz,phi,omega,kappa,m (leave it out to fix none)"), false;
  if (!fix_text.empty() && !parseFixList(fix_text, fixes))
    return (why = "-fix expects a comma list of tx,ty,tz,phi,omega,kappa,m"), false;
  for (int i : fixes)
    settings.fixParameter(i);
  settings.max_iterations = max_iter;
  settings.source_thinning = thin;
  settings.guess_uncertainty = guess;
  if (max_dist_given)
    settings.max_correspondence_distance = max_dist;
  if (!settings.isValid(&why))
    return (why = "invalid settings: " + why), false;
  if (!(o.K > 0.0) || !std::isfinite(o.K))
    return (why = "-K must be > 0"), false;
  return true;
}

/// Inputs, settings, outputs and the -truth file: all refused before a point cloud is read
/// (outputs must be writable and must not clobber inputs or existing files).
bool
parseOptions(int argc, char** argv, Options& o, std::string& why)
{
  // Positional files and the known options (anything else starting with '-' is an error).
  static const std::set<std::string> valued = {"-o",        "-rule", "-params", "-fix",
                                               "-max_iter", "-K",    "-thin",   "-max_dist",
                                               "-guess",    "-json", "-truth",  "-classes"};
  std::vector<std::string> files;
  if (!pcl_ls3d::tools::splitArguments(argc, argv, 1, valued, {"-overwrite"}, files, why))
    return false;
  if (files.size() != 2)
    return (why = "expected exactly two input files, SOURCE and TARGET (see -h)"), false;
  o.source_path = files[0];
  o.target_path = files[1];
  o.overwrite = find_switch(argc, argv, "-overwrite");
  parse_argument(argc, argv, "-o", o.out_path);
  parse_argument(argc, argv, "-json", o.json_path);
  parse_argument(argc, argv, "-truth", o.truth_path);
  if (parse_argument(argc, argv, "-classes", o.classes_text) >= 0 &&
      !pcl_ls3d::tools::parseClassList("-classes", o.classes_text, o.classes, why))
    return false;
  if (!parseSettings(argc, argv, o, why))
    return false;
  const std::vector<std::string> inputs = {o.source_path, o.target_path, o.truth_path};
  if (!pcl_ls3d::tools::checkOutputFile(o.out_path, inputs, o.overwrite, why, true) ||
      !pcl_ls3d::tools::checkOutputFile(o.json_path, inputs, o.overwrite, why))
    return false;
  if (!o.out_path.empty() && pcl_ls3d::io::isSameFile(o.out_path, o.json_path))
    return (why = "-o and -json name the same file"), false;
  return o.truth_path.empty() || readTruth(o.truth_path, o.truth, why);
}

/// The two clouds (io::loadCloudPair: the target first, the source in the target's local origin,
/// heights in the plan unit around working_origin); with -classes, the points matched
/// (whole_source: every point -o moves).
struct Pair : pcl_ls3d::io::CloudPair
{
  Cloud::Ptr whole_source;
  double load_ms = 0.0;
};

bool
loadPair(const Options& o, Pair& pair, std::string& error)
{
  TicToc tt;
  tt.tic();
  if (!pcl_ls3d::io::loadCloudPair(o.target_path, o.source_path, pair, error))
    return false;
  pcl_ls3d::tools::printPairNotes(pair);
  pair.whole_source = pair.source;
  const std::size_t target_points = pair.target->size();
  if (!keepClasses(pair.target, o.classes, o.target_path, error) ||
      !keepClasses(pair.source, o.classes, o.source_path, error))
    return false;
  if (!o.classes.empty())
    print_info("Matching on classes %s: %zu of %zu target and %zu of %zu source points\n",
               o.classes_text.c_str(), pair.target->size(), target_points, pair.source->size(),
               pair.whole_source->size());
  pair.load_ms = tt.toc();
  print_info("Loaded target %s (%zu points) and source %s (%zu points), local origin (%.3f, %.3f, %.3f) in "
             "%.0f ms\n",
             o.target_path.c_str(), pair.target->size(), o.source_path.c_str(), pair.source->size(),
             pair.target_info.origin.x(), pair.target_info.origin.y(), pair.target_info.origin.z(),
             pair.load_ms);
  return true;
}

/// LS3D with the Zuo estimator; the library's own PCL_ERROR would be a second error line (the
/// report's message is printed instead).
void
adjust(const Options& o, const Pair& pair, LS3D& ls3d, Cloud& aligned)
{
  ls3d.setAdjustmentSettings(o.settings);
  ls3d.setConjugateRule(o.rule);
  ls3d.setRobustEstimator(std::make_shared<pcl_ls3d::ZuoEstimator>(o.K));
  ls3d.setInputSource(pair.source);
  ls3d.setInputTarget(pair.target);
  const auto verbosity = getVerbosityLevel();
  setVerbosityLevel(L_ALWAYS);
  ls3d.align(aligned);
  setVerbosityLevel(verbosity);
}

/// No estimate at all: the JSON still says why, for a pipeline reading it.
int
failWithoutEstimate(const Options& o, const pcl_ls3d::AdjustmentReport& r)
{
  const nlohmann::json j = {{"converged", false},
                            {"termination", pcl_ls3d::terminationTypeToString(r.termination)},
                            {"message", r.message},
                            {"iterations", r.iterations},
                            {"transformation", nullptr}};
  if (!o.json_path.empty() && !pcl_ls3d::tools::writeJsonFile(o.json_path, j))
    return fail("cannot write " + o.json_path), 1;
  return fail(std::string("registration failed: ") + pcl_ls3d::terminationTypeToString(r.termination) + ": " +
              r.message),
         1;
}

/// -truth: the error of the transformation over every point -o moves, printed and in the JSON
/// (working coordinates: lengths in the plan unit).
void
reportTruthError(const Pair& pair, const Eigen::Matrix4d& T_working, const Eigen::Matrix4d& truth,
                 nlohmann::json& j)
{
  const Cloud& whole = *pair.whole_source;
  Eigen::Matrix3Xd pts(3, static_cast<Eigen::Index>(whole.size()));
  for (std::size_t i = 0; i < whole.size(); ++i)
    pts.col(static_cast<Eigen::Index>(i)) = whole[i].getVector3fMap().cast<double>() + pair.working_origin;
  const auto e = pcl_ls3d::evaluation::computeTransformError(T_working, pair.heights.toWorking(truth), pts);
  // Significant digits: a fixed 4 decimals would show a 0.05 mm error on metre data as 0.
  print_info("Error vs truth: mean displacement %.3g, max %.3g, max over bbox %.3g\n", e.mean, e.max,
             e.max_bbox);
  j["truth_error"] = {
      {"mean_displacement", e.mean}, {"max_displacement", e.max}, {"max_displacement_bbox", e.max_bbox}};
}

/// -o: the source moved (a LAS source to LAS record by record, with its header and VLRs, so its
/// CRS and height unit; any other output in the target's frame, CRS and height unit).
bool
writeAligned(const Options& o, const Pair& pair, const pcl_ls3d::AdjustmentReport& r,
             const Eigen::Matrix4d& T_working, Cloud& aligned, std::string& error)
{
  TicToc tt;
  tt.tic();
  pcl_ls3d::io::SaveOptions so;
  so.overwrite = o.overwrite;
  // The aligned source lies in the target's frame: the target's CRS, else the source's.
  const std::string target_crs = pcl_ls3d::maps::crsOfFile(pair.target_info);
  pcl_ls3d::maps::recordCrs(target_crs.empty() ? pcl_ls3d::maps::crsOfFile(pair.source_info) : target_crs,
                            so);
  const std::string out_ext = pcl_ls3d::io::fileExtension(o.out_path);
  const bool las_to_las = pair.source_info.format == "las" && (out_ext == "las" || out_ext == "laz");
  if (!o.classes.empty() && !las_to_las)
    pcl::transformPointCloud(*pair.whole_source, aligned, Eigen::Matrix4f(r.transformation.cast<float>()));
  if (!las_to_las)  // the target's height unit again
    pcl_ls3d::heightsToFile(aligned, pair.heights.target, pair.heights.target, pair.target_info.origin.z());
  const pcl_ls3d::HeightUnits in_source_units = pcl_ls3d::HeightUnits::ofOneFile(pair.heights.source);
  if (las_to_las
          ? !writeMovedLas(o.source_path, in_source_units.toFiles(T_working), o.out_path, o.overwrite, error)
          : !pcl_ls3d::io::saveCloud(o.out_path, aligned, pair.target_info.origin, error, so))
    return false;
  print_info("Wrote %s in %.0f ms\n", o.out_path.c_str(), tt.toc());
  return true;
}

}  // namespace

int
main(int argc, char** argv)
{
  pcl_ls3d::tools::lineBufferedStdout();
  if (find_switch(argc, argv, "-h") || find_switch(argc, argv, "--help")) {
    printHelp(argv[0]);
    return 0;
  }
  Options o;
  Pair pair;
  std::string error;
  if (!parseOptions(argc, argv, o, error) || !loadPair(o, pair, error))
    return fail(error), 1;

  TicToc tt;
  tt.tic();
  LS3D ls3d;
  Cloud aligned;
  adjust(o, pair, ls3d, aligned);
  const double t_align = tt.toc();
  const pcl_ls3d::AdjustmentReport& r = ls3d.getReport();
  if (!r.hasEstimate())
    return failWithoutEstimate(o, r);
  // An estimate that failed the quality gate is shown (and in the JSON) but not written out.
  const bool trusted = r.isSolutionUsable();

  // Report: the local transform re-expressed in input coordinates (both clouds share the origin).
  const Eigen::Vector3d& origin = pair.working_origin;
  const Eigen::Matrix4d T_working = pcl_ls3d::localToGlobal(r.transformation, origin, origin);
  const Eigen::Matrix4d T_input = pair.heights.toFiles(T_working);
  print_info("%s", r.fullReport().c_str());
  pcl_ls3d::tools::printTransformation("Transformation (SOURCE -> TARGET, input coordinates):", T_input);
  print_info("Timings: load %.0f ms, adjustment %.0f ms\n", pair.load_ms, t_align);
  pcl_ls3d::ReportFrame frame;
  frame.transformation = T_input;
  frame.origin = origin;
  frame.cloud_origin = pair.target_info.origin;
  nlohmann::json j = nlohmann::json::parse(pcl_ls3d::adjustmentReportJson(r, ls3d.hasConverged(), frame));
  if (pair.heights.converts())
    j["heights"] = pcl_ls3d::heightUnitsJson(pair.heights);
  j["timings_ms"] = {{"load", pair.load_ms}, {"adjust", t_align}};
  if (!o.truth_path.empty())
    reportTruthError(pair, T_working, o.truth, j);

  if (!o.out_path.empty() && trusted && !writeAligned(o, pair, r, T_working, aligned, error))
    return fail(error), 1;
  if (!o.json_path.empty() && !pcl_ls3d::tools::writeJsonFile(o.json_path, j))
    return fail("cannot write " + o.json_path), 1;
  if (!trusted)
    return fail(std::string("registration not trustworthy: ") +
                pcl_ls3d::terminationTypeToString(r.termination) + ": " + r.message +
                (o.out_path.empty() ? "" : " (" + o.out_path + " not written)")),
           3;
  return 0;
}
