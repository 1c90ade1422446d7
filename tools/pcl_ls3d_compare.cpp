/// \file pcl_ls3d_compare.cpp
/// \brief Registers SOURCE to TARGET with LS3D (LND, LZD, ICP rules) and PCL's ICP, point-to-plane
///        ICP, GICP and NDT on the same input, and prints one table (iterations, wall time, RMS /
///        σ0, converged; with -truth the displacement and parameter errors). -json writes the same.
///        On request also the robust estimators of issue 9 (-methods robust).

#include "tool_options.h"
#include "tool_output.h"

#include <pcl_ls3d/evaluation/comparison_report.h>
#include <pcl_ls3d/evaluation/ls3d_method.h>
#include <pcl_ls3d/evaluation/pcl_methods.h>
#include <pcl_ls3d/evaluation/robust_method.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/cloud_pair.h>
#include <pcl_ls3d/maps/coordinate_reference.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl::console;
using namespace pcl_ls3d::evaluation;

namespace {

const std::set<std::string> kValueOptions = {"-truth",   "-json",     "-methods",  "-max_corr", "-iter",
                                             "-ndt_res", "-rms_dist", "-thinning", "-gicp_grad"};
const std::set<std::string> kSwitches = {"-overwrite", "-h", "--help"};
const std::vector<std::string> kAllMethods = {"ls3d-lnd", "ls3d-lzd", "ls3d-icp", "icp",
                                              "icpn",     "gicp",     "ndt"};
// Robust matching (issue 9; Li et al. 2001): selected by name or "robust", not part of "all".
const std::vector<std::string> kRobustMethods = {"robust-m", "robust-md", "robust-lms", "robust-mm"};

void
printHelp(const char* name)
{
  print_error("Syntax is: %s SOURCE TARGET [options]\n", name);
  print_info("  Registers SOURCE to TARGET (PCD, PLY, LAS, XYZ; both shifted to TARGET's local origin)\n"
             "  from the identity with every method and prints one comparison table. Columns: conv =\n"
             "  stopped by its own criterion before the iteration limit with a finite result; trust =\n"
             "  LS3D's quality gate (- for PCL's methods: their hasConverged() is no such check).\n"
             "  Exits 1 when no method converged. Lengths are in the data's unit: that of the CRS an\n"
             "  input declares (LAS, or a PCD / PLY header: m, ft), else \"units\"; heights in\n"
             "  another unit than the plan are matched in the plan unit. A run without an\n"
             "  estimate shows \"-\" (JSON null).\n"
             "  -truth FILE   : truth JSON with \"transformation\": 4x4 row-major source->target in file\n"
             "                  coordinates (as written by pcl_ls3d_synth); adds displacement errors\n"
             "                  (mean/max over the source points, max over its bbox corners) and the\n"
             "                  7 parameter errors (in the common local frame)\n"
             "  -json FILE    : also write the results as JSON\n"
             "  -methods LIST : comma-separated subset of ls3d-lnd,ls3d-lzd,ls3d-icp,icp,icpn,gicp,ndt\n"
             "                  (also: all, ls3d, pcl; default all), and the robust estimators of\n"
             "                  pcl_ls3d_deformation robust-m,robust-md,robust-lms,robust-mm (also:\n"
             "                  robust; LZD rule, 6 parameters, their own defaults: -max_corr and\n"
             "                  -iter do not apply; the sigma0 column is their robust scale)\n"
             "  -max_corr D   : max correspondence distance for every method (default 2 m). Default\n"
             "                  lengths are metres, converted when an input's CRS declares another\n"
             "                  unit (feet); without a CRS they are taken as they are (2 units).\n"
             "                  Lengths given here are in the data's unit.\n"
             "  -iter N       : max iterations: LS3D (default 30) and PCL (default 50) both set to N\n"
             "  -ndt_res R    : NDT voxel edge (default 2 m)\n"
             "  -thinning S   : LS3D source thinning voxel (default 0 = all points)\n"
             "  -gicp_grad G  : GICP inner BFGS gradient tolerance (see pcl_methods.h)\n"
             "  -rms_dist D   : NN distance cut-off of the RMS column (default 1 m)\n"
             "  -overwrite    : replace an existing -json file (never an input)\n"
             "  -h            : this help\n");
}

/// A length or tolerance option: a finite number > 0 (>= 0 with `zero_ok`), said plainly when it
/// is not.
bool
positiveOption(int argc, char** argv, const std::string& name, double& value, bool zero_ok, std::string& why)
{
  if (!pcl_ls3d::tools::numberOption(argc, argv, name, value, why))
    return false;
  if (value > 0.0 || (zero_ok && value == 0.0))
    return true;
  why = name + (zero_ok ? " must be >= 0" : " must be > 0");
  return false;
}

/// The CRS of the data's lengths: the first that an input declares with a length unit (target
/// first); empty when none does.
std::string
lengthCrs(const pcl_ls3d::io::CloudInfo& target, const pcl_ls3d::io::CloudInfo& source)
{
  for (const pcl_ls3d::io::CloudInfo* info : {&target, &source})
    if (std::string wkt = pcl_ls3d::maps::crsOfFile(*info); pcl_ls3d::maps::crsLinearUnit(wkt) > 0.0)
      return wkt;
  return "";
}

/// Expands the -methods list; false on an unknown name.
bool
parseMethods(const std::string& text, std::vector<std::string>& out, std::string& why)
{
  std::stringstream ss(text);
  std::string item;
  std::set<std::string> chosen;
  while (std::getline(ss, item, ',')) {
    if (item == "all")
      chosen.insert(kAllMethods.begin(), kAllMethods.end());
    else if (item == "ls3d")
      chosen.insert({"ls3d-lnd", "ls3d-lzd", "ls3d-icp"});
    else if (item == "pcl")
      chosen.insert({"icp", "icpn", "gicp", "ndt"});
    else if (item == "robust")
      chosen.insert(kRobustMethods.begin(), kRobustMethods.end());
    else if (std::find(kAllMethods.begin(), kAllMethods.end(), item) != kAllMethods.end() ||
             std::find(kRobustMethods.begin(), kRobustMethods.end(), item) != kRobustMethods.end())
      chosen.insert(item);
    else {
      why = "unknown method '" + item + "' in -methods";
      return false;
    }
  }
  for (const auto& list : {kAllMethods, kRobustMethods})  // table order
    for (const auto& m : list)
      if (chosen.count(m))
        out.push_back(m);
  if (out.empty())
    why = "-methods selects nothing";
  return !out.empty();
}

/// Reads "transformation" (4×4 row-major, file coordinates) from a truth JSON.
bool
loadTruth(const std::string& path, Eigen::Matrix4d& T, std::string& why)
{
  std::ifstream in(path);
  if (!in) {
    why = "cannot open truth file " + path;
    return false;
  }
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    const auto& rows = j.at("transformation");
    if (!rows.is_array() || rows.size() != 4)
      throw std::runtime_error("\"transformation\" is not 4 rows");
    for (int r = 0; r < 4; ++r) {
      const auto& row = rows.at(static_cast<std::size_t>(r));
      if (!row.is_array() || row.size() != 4)
        throw std::runtime_error("\"transformation\" row is not 4 numbers");
      for (int c = 0; c < 4; ++c)
        T(r, c) = row.at(static_cast<std::size_t>(c)).get<double>();
    }
  } catch (const std::exception& e) {
    why = "bad truth file " + path + ": " + e.what();
    return false;
  }
  if (!T.allFinite() || !T.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1))) {
    why = "truth transformation in " + path + " is not a finite 4x4 similarity";
    return false;
  }
  return true;
}

RegistrationRun
runMethod(const std::string& m, const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& source,
          const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& target, const PclMethodSettings& ps,
          const Ls3dMethodSettings& ls)
{
  using pcl_ls3d::ConjugateRuleType;
  if (m == "ls3d-lnd")
    return runLs3d(ConjugateRuleType::LND, source, target, ls);
  if (m == "ls3d-lzd")
    return runLs3d(ConjugateRuleType::LZD, source, target, ls);
  if (m == "ls3d-icp")
    return runLs3d(ConjugateRuleType::ICP, source, target, ls);
  pcl_ls3d::RobustMethod robust;
  if (m.rfind("robust-", 0) == 0 && pcl_ls3d::parseRobustMethod(m.substr(7), robust))
    return runRobust(robust, source, target);
  if (m == "icp")
    return runPclMethod(PclMethod::ICP, source, target, ps);
  if (m == "icpn")
    return runPclMethod(PclMethod::ICP_NORMALS, source, target, ps);
  if (m == "gicp")
    return runPclMethod(PclMethod::GICP, source, target, ps);
  return runPclMethod(PclMethod::NDT, source, target, ps);
}

int
fail(const std::string& why)
{
  print_error("%s\n", why.c_str());
  return 1;
}

/// Everything the command line asks for, checked before the clouds are read.
struct Options
{
  std::string source_path, target_path, truth_path, json_path;
  std::vector<std::string> methods;
  bool overwrite = false;
  PclMethodSettings ps;
  Ls3dMethodSettings ls;
  double rms_dist = 1.0;                ///< RMS over nearest-neighbour distances within this
  std::set<std::string> given_lengths;  ///< length options on the command line (data's unit)
  bool has_truth = false;
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity();  ///< input coordinates
};

bool
parseOptions(int argc, char** argv, Options& o, std::string& why)
{
  std::vector<std::string> files;
  if (!pcl_ls3d::tools::splitArguments(argc, argv, 1, kValueOptions, kSwitches, files, why))
    return false;
  if (files.size() != 2)
    return (why = "expected exactly two input files (SOURCE TARGET), got " + std::to_string(files.size())),
           false;
  o.source_path = files[0];
  o.target_path = files[1];
  std::string methods_text = "all";
  parse_argument(argc, argv, "-truth", o.truth_path);
  parse_argument(argc, argv, "-json", o.json_path);
  parse_argument(argc, argv, "-methods", methods_text);
  o.overwrite = find_switch(argc, argv, "-overwrite");
  double max_corr = o.ps.max_correspondence_distance, ndt_res = o.ps.ndt_resolution;
  double thinning = 0.0;
  int iterations = 0;
  if (!positiveOption(argc, argv, "-max_corr", max_corr, false, why) ||
      !positiveOption(argc, argv, "-ndt_res", ndt_res, false, why) ||
      !positiveOption(argc, argv, "-rms_dist", o.rms_dist, false, why) ||
      !positiveOption(argc, argv, "-thinning", thinning, true, why) ||
      !positiveOption(argc, argv, "-gicp_grad", o.ps.gicp_gradient_tolerance, false, why) ||
      !pcl_ls3d::tools::integerOption(argc, argv, "-iter", iterations, why, 1, 1000000))
    return false;
  o.ps.max_correspondence_distance = o.ls.max_correspondence_distance = max_corr;
  o.ps.ndt_resolution = ndt_res;
  for (const char* name : {"-max_corr", "-ndt_res", "-rms_dist", "-thinning"})
    if (find_argument(argc, argv, name) >= 0)
      o.given_lengths.insert(name);
  o.ls.source_thinning = thinning;
  if (iterations > 0)
    o.ps.max_iterations = o.ls.max_iterations = iterations;
  if (!parseMethods(methods_text, o.methods, why) ||
      !pcl_ls3d::tools::checkOutputFile(o.json_path, {o.source_path, o.target_path, o.truth_path},
                                        o.overwrite, why))
    return false;
  o.has_truth = !o.truth_path.empty();  // read before the clouds
  return !o.has_truth || loadTruth(o.truth_path, o.truth, why);
}

/// Both clouds in one local frame: the target first, the source in its origin.
struct Clouds
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr source, target;
  pcl_ls3d::io::CloudInfo source_info, target_info;
  /// Heights in another unit than the plan are matched in the plan unit (working coordinates,
  /// around working_origin); the files' origin is target_info.origin.
  pcl_ls3d::HeightUnits heights;
  Eigen::Vector3d working_origin = Eigen::Vector3d::Zero();
};

bool
loadClouds(const Options& o, Clouds& c, std::string& why)
{
  TicToc tt;
  tt.tic();
  pcl_ls3d::io::CloudPair pair;
  if (!pcl_ls3d::io::loadCloudPair(o.target_path, o.source_path, pair, why))
    return false;
  pcl_ls3d::tools::printPairNotes(pair);
  c.source = toXYZ(*pair.source);
  c.target = toXYZ(*pair.target);
  c.source_info = pair.source_info;
  c.target_info = pair.target_info;
  c.heights = pair.heights;
  c.working_origin = pair.working_origin;
  print_info("Loaded source %s (%zu points) and target %s (%zu points), local origin "
             "(%.3f, %.3f, %.3f), in %.0f ms\n",
             o.source_path.c_str(), c.source->size(), o.target_path.c_str(), c.target->size(),
             c.target_info.origin.x(), c.target_info.origin.y(), c.target_info.origin.z(), tt.toc());
  return true;
}

/// Every method on the same pair, scored in the same process; returns how many were usable.
std::size_t
runAll(const Options& o, const Clouds& c, std::vector<RegistrationRun>& runs)
{
  const Eigen::Vector3d& origin = c.working_origin;
  const Eigen::Matrix4d truth_local =
      o.has_truth ? pcl_ls3d::globalToLocal(c.heights.toWorking(o.truth), origin, origin)
                  : Eigen::Matrix4d::Identity();
  RunEvaluation evaluation(c.source, c.target, o.rms_dist);
  std::size_t usable = 0;
  for (const auto& m : o.methods) {
    print_info("Running %s ... ", m.c_str());
    {  // PCL's own warnings and errors would land in the middle of the table: the row says it
      const auto verbosity = getVerbosityLevel();
      setVerbosityLevel(L_ALWAYS);
      runs.push_back(runMethod(m, c.source, c.target, o.ps, o.ls));
      setVerbosityLevel(verbosity);
    }
    evaluation.evaluate(runs.back(), o.has_truth ? &truth_local : nullptr);
    const RegistrationRun& r = runs.back();
    // Converged by its own criterion (not at the iteration limit; for LS3D and the robust rows
    // also past the quality gate, which turns a refused CONVERGED into UNRELIABLE) and finite.
    const bool ok = r.ran && r.converged && r.transformation.allFinite();
    usable += ok;
    print_info("%.3f s%s%s\n", r.time_s, ok ? "" : ", failed: ", ok ? "" : r.message.c_str());
  }
  return usable;
}

bool
writeJson(const Options& o, const Clouds& c, const std::vector<RegistrationRun>& runs,
          const std::string& unit, std::string& why)
{
  ComparisonContext context;
  context.source = o.source_path;
  context.target = o.target_path;
  context.origin = c.working_origin;
  context.heights = c.heights;
  context.file_origin = c.target_info.origin;
  context.source_points = c.source->size();
  context.target_points = c.target->size();
  context.has_truth = o.has_truth;
  context.rms_max_distance = o.rms_dist;
  context.unit = unit;
  context.pcl_settings = o.ps.describe(unit);
  context.ls3d_settings = o.ls.describe(unit);
  std::ofstream out(o.json_path);
  out << comparisonJson(runs, context) << "\n";
  if (!out)
    return (why = "cannot write " + o.json_path), false;
  print_info("Wrote %s\n", o.json_path.c_str());
  return true;
}

/// The default lengths are metres: on data whose CRS declares another unit (feet) they are
/// converted, so that a comparison means the same in either unit. Lengths given on the command
/// line are the data's unit already.
void
defaultsInDataUnit(double metres_per_unit, const std::string& unit, Options& o)
{
  if (!(metres_per_unit > 0.0) || metres_per_unit == 1.0)
    return;
  const auto given = [&o](const char* name) { return o.given_lengths.count(name) > 0; };
  PclMethodSettings pcl_settings = o.ps.inUnit(metres_per_unit);
  Ls3dMethodSettings ls3d_settings = o.ls.inUnit(metres_per_unit);
  if (given("-max_corr"))
    pcl_settings.max_correspondence_distance = ls3d_settings.max_correspondence_distance =
        o.ps.max_correspondence_distance;
  if (given("-ndt_res"))
    pcl_settings.ndt_resolution = o.ps.ndt_resolution;
  if (given("-thinning"))
    ls3d_settings.source_thinning = o.ls.source_thinning;
  if (!given("-rms_dist"))
    o.rms_dist /= metres_per_unit;
  o.ps = pcl_settings;
  o.ls = ls3d_settings;
  print_info("Default lengths are metres, converted to %s (%g m)\n", unit.c_str(), metres_per_unit);
}

}  // namespace

int
main(int argc, char** argv)
{
  pcl_ls3d::tools::lineBufferedStdout();
  if (find_switch(argc, argv, "-h") || find_switch(argc, argv, "--help") || argc < 2) {
    printHelp(argv[0]);
    return argc < 2 ? 1 : 0;
  }
  Options o;
  Clouds c;
  std::string why;
  if (!parseOptions(argc, argv, o, why) || !loadClouds(o, c, why))
    return fail(why);
  // Lengths are in the unit of the CRS an input declares, else "units" (and taken as they are).
  const std::string crs = lengthCrs(c.target_info, c.source_info);
  const std::string unit = crs.empty() ? "units" : pcl_ls3d::maps::crsLinearUnitName(crs);
  defaultsInDataUnit(pcl_ls3d::maps::crsLinearUnit(crs), unit, o);
  print_info("PCL settings : %s\nLS3D settings: %s\n", o.ps.describe(unit).c_str(),
             o.ls.describe(unit).c_str());
  std::vector<RegistrationRun> runs;
  const std::size_t usable = runAll(o, c, runs);
  std::printf("\n%s", formatComparisonTable(runs, o.has_truth, unit).c_str());
  std::printf("RMS: nearest-neighbour distances within %g %s. %s\n", o.rms_dist, unit.c_str(),
              o.has_truth ? "Errors vs truth; parameter errors in the local frame "
                            "(rotation about the local origin)."
                          : "");
  if (!o.json_path.empty() && !writeJson(o, c, runs, unit, why))
    return fail(why);
  if (usable == 0)
    return fail("every method failed on " + o.source_path + " -> " + o.target_path);
  return 0;
}
