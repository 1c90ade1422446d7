// pcl_ls3d_deformation: robust matching of EPOCH onto REFERENCE and the map of what moved
// (Li et al. 2001; issue 9).
#include "tool_options.h"
#include "tool_output.h"

#include <pcl_ls3d/common/similarity_transform.h>
#include <pcl_ls3d/deformation/deformation_analysis.h>
#include <pcl_ls3d/deformation/deformation_map.h>
#include <pcl_ls3d/deformation/point_residual.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/cloud_pair.h>
#include <pcl_ls3d/io/json_text.h>
#include <pcl_ls3d/io/pcd_io.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/search/flann_kd_tree.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/search/kdtree.h>

#include <nlohmann/json.hpp>

#include <algorithm>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

using namespace pcl::console;
using Cloud = pcl::PointCloud<pcl_ls3d::PointLiDAR>;
namespace def = pcl_ls3d::deformation;

namespace {

// Above this share of the observed area deformed, which part is stable is a close call: a
// robust estimator takes the larger one, and a border the rule cannot observe (LND beside a
// one-sided neighbourhood) shifts the balance by several per cent.
constexpr double kNearHalfPercent = 40.0;

void
printHelp(const char* prog)
{
  print_info("Local deformation between two epochs of a surface: robust matching of EPOCH onto REFERENCE\n"
             "(the transformation of the stable part, no control points; up to half the surface may have\n"
             "moved), then the residual of every epoch point, its sigma, significance and the connected\n"
             "deformed regions (Li, Xu, Chen & Tsai 2001).\n\n"
             "Usage: %s REFERENCE EPOCH [options]\n"
             "  REFERENCE, EPOCH     .las .laz .copc.laz .pcd .ply .xyz/.txt (a gridded DEM as x y z text "
             "works too;\n"
             "                       the reference is loaded first, the epoch uses its local origin)\n"
             "  -estimator NAME      mm (default: LTS start + Tukey M-step, high breakdown and 95 %%\n"
             "                       efficiency), lms (Li: LMS subsets then M), md (Li's M-D), m (Tukey on\n"
             "                       MAD), huber, zuo, ls (plain least squares). mm and lms also fit from\n"
             "                       a block start and keep the fit whose stable part scatters least\n"
             "  -rule lzd|lnd        residuals along z (LHD, default) or along the surface normal\n"
             "  -params 6|7|3        rigid (default), similarity, translation. Without -params, a\n"
             "                       rigid fit the surface does not determine (nearly flat terrain)\n"
             "                       is replaced by the translation alone, with a note; with it, the\n"
             "                       model named or a refusal\n"
             "  -subsets N           random subsets per search round for lms/mm (default: lms from Li\n"
             "                       eq. 12, at least 3000 above 40 %% contamination; mm 500 FAST-LTS\n"
             "                       starts); up to 3 rounds, re-linearised while the fit moves, so a run\n"
             "                       reports up to 3 N subsets (mm: 1500)\n"
             "  -contamination E     share of the surface that may have moved, for eq. 12 (default 0.5)\n"
             "  -seed S              random seed of the subsets (default 1)\n"
             "  -k K                 significance |r| > K sigma (default 3)\n"
             "  -lod95               significance by an M3C2-style level of detection at 95 %% instead\n"
             "                       (not with -k)\n"
             "  -min_region N        smaller connected detections are noise (default 10 points)\n"
             "  -grow_k G            regions grow into adjacent points of their sign with |r| > G sigma\n"
             "                       (hysteresis; default 2, 0: off; below K, with -lod95 below 1.96)\n"
             "  -refine N            rounds of the stable-part refinement: the regions and their rim\n"
             "                       left out, the rest matched again until that set repeats (default at\n"
             "                       most 10; 0: the estimator's\n"
             "                       own answer, as in Li et al.)\n"
             "  -max_dist d          maximum correspondence distance (default unlimited)\n"
             "  -max_iter N          iterations of each adjustment (default 30; at the limit: exit 3)\n"
             "  -matching_points N   match on at most N evenly spread epoch points (default 50000; 0:\n"
             "                       all); residuals are computed for every point\n"
             "  -o RESIDUALS.pcd     one record per epoch point, epoch order: x y z (local coordinates,\n"
             "                       origin and CRS in the header, origin in the JSON) residual sigma\n"
             "                       significant region; .xyz/.txt: the same as text with full file\n"
             "                       coordinates\n"
             "  -json REPORT         transformation (4x4 row-major, EPOCH -> REFERENCE, input\n"
             "                       coordinates), converged, parameters and sigmas (reduced frame about\n"
             "                       local_origin_source / local_origin_target), params (free\n"
             "                       parameters; model_note when fewer than asked), estimator, scale,\n"
             "                       subsets, percent_deformed, regions\n"
             "  -map PREFIX          PREFIX.png, .pdf or .svg (residual map, diverging colour bar,\n"
             "                       significant regions outlined) and PREFIX.tif (float32 GeoTIFF of\n"
             "                       the residuals, NaN where no point has one, with the CRS of -crs or\n"
             "                       the reference's)\n"
             "  -map_format F        png (default), pdf or svg: the map as PREFIX.F (pdf and svg: vector\n"
             "                       graphics for reports)\n"
             "  -map_cell C          map cell edge (default 1.5 point spacings; irregular airborne data:\n"
             "                       about 2.5 spacings, so that most cells hold points)\n"
             "  -crs CRS             coordinate reference of the inputs for the GeoTIFF (EPSG:26917, a\n"
             "                       PROJ string or WKT; default: the CRS the reference declares in its\n"
             "                       LAS VLRs or its PCD / PLY header, if any); also the units of an\n"
             "                       input that declares no CRS (heights in another unit than the plan\n"
             "                       are converted to the plan unit for the matching)\n"
             "  -overwrite           allow replacing existing output files\n"
             "  -h                   this help\n"
             "Exit status: 0 done; 1 bad input or the matching failed (nothing written); 3 the matching\n"
             "did not converge (MAX_ITERATIONS: outputs written, marked \"converged\": false).\n",
             prog);
}

/// -lod95's significance threshold in sigmas of the level of detection (residual_field.cpp).
constexpr double kLod95Factor = 1.96;

/// Options that contradict each other, refused before any work: -k has no use with -lod95 (its
/// threshold is the level of detection), and growing at or above the detection threshold adds
/// no point to a region.
bool
optionConflict(int argc, char** argv, bool lod95, double k, double grow_k, std::string& why)
{
  const char* k_text = pcl_ls3d::tools::optionValue(argc, argv, "-k");
  const char* grow_text = pcl_ls3d::tools::optionValue(argc, argv, "-grow_k");
  if (lod95 && k_text) {
    why = "-k and -lod95 exclude each other: -lod95 tests the 95 % level of detection, not K sigma";
    return false;
  }
  const double detection = lod95 ? kLod95Factor : k;  // the significance threshold in sigmas
  if (!grow_text || !(grow_k > 0.0 && grow_k >= detection))
    return true;
  char buf[160];
  std::snprintf(buf, sizeof(buf),
                "-grow_k %g must be below %s (%g): regions grow into weaker neighbours "
                "(-grow_k 0: off)",
                grow_k, lod95 ? "-lod95's threshold" : "-k", detection);
  why = buf;
  return false;
}

bool
fail(const std::string& message)
{
  print_error("%s\n", message.c_str());
  return false;
}

/// The parameters, their frame (its origins in input coordinates) and their sigmas; an exact fit
/// (sigma0 = 0) has none, worded as pcl_ls3d_register's report.
void
printParameters(const pcl_ls3d::AdjustmentReport& a, const Eigen::Vector3d& o_s, const Eigen::Vector3d& o_t,
                bool heights_converted)
{
  print_info("Parameters in the reduced frame x_ref - o_t = t + m R (x_epoch - o_s), %s,\n"
             "  o_s (%.4f, %.4f, %.4f), o_t (%.4f, %.4f, %.4f): t is the shift beyond o_t - o_s\n ",
             heights_converted ? "input coordinates with heights in the plan unit" : "input coordinates",
             o_s.x(), o_s.y(), o_s.z(), o_t.x(), o_t.y(), o_t.z());
  const auto& names = pcl_ls3d::similarityParameterNames();
  bool exact_fit = false;  // the only case with NaN sigmas (fixed ones are 0)
  for (int i = 0; i < 7; ++i)
    exact_fit = exact_fit || std::isnan(a.sigmas[i]);
  for (int i = 0; i < 7; ++i) {
    print_info(" %s %.6g", names[static_cast<std::size_t>(i)].c_str(), a.parameters[i]);
    if (!exact_fit)
      print_info(" (%.2g)", a.sigmas[i]);
  }
  print_info(exact_fit ? "; sigma not estimable (exact fit)\n" : "\n");
}

using pcl_ls3d::tools::finiteOrNull;

nlohmann::json
matrixJson(const Eigen::Matrix4d& T)
{
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r)
    rows.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
  return rows;
}

nlohmann::json
regionJson(const def::DeformationRegion& r, const Eigen::Vector3d& origin,
           const pcl_ls3d::HeightUnits& heights)
{
  // The epoch's points, in its file's coordinates.
  const Eigen::Vector3d c = heights.sourceToFile(r.centroid + origin),
                        lo = heights.sourceToFile(r.box_min + origin),
                        hi = heights.sourceToFile(r.box_max + origin);
  return {{"id", r.id},
          {"sign", r.sign},
          {"points", r.points},
          {"area", r.area},
          {"mean", r.mean},
          {"max", r.max},
          {"min", r.min},
          {"volume", r.volume},
          {"centroid", {c.x(), c.y(), c.z()}},
          {"box_min", {lo.x(), lo.y(), lo.z()}},
          {"box_max", {hi.x(), hi.y(), hi.z()}}};
}

bool
writeResiduals(const std::string& path, const Cloud& epoch, const def::DeformationResult& r,
               const Eigen::Vector3d& origin, const std::string& crs_wkt, std::string& error)
{
  const std::string ext = pcl_ls3d::io::fileExtension(path);
  if (ext == "xyz" || ext == "txt") {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f)
      return (error = "cannot write " + path).empty();
    std::fprintf(f, "# x y z residual sigma significant region\n");
    for (std::size_t i = 0; i < epoch.size(); ++i) {
      const Eigen::Vector3d p = epoch[i].getVector3fMap().cast<double>() + origin;
      std::fprintf(f, "%.3f %.3f %.3f %.4f %.4f %d %d\n", p.x(), p.y(), p.z(), r.field.residual[i],
                   r.field.sigma[i], static_cast<int>(r.field.significant[i]), r.regions.region[i]);
    }
    if (std::fclose(f) != 0)
      return (error = "cannot write " + path).empty();
    return true;
  }
  if (ext != "pcd")
    return (error = "-o writes .pcd, .xyz or .txt, not ." + ext).empty();
  pcl::PointCloud<pcl_ls3d::PointResidual> out;
  out.resize(epoch.size());
  for (std::size_t i = 0; i < epoch.size(); ++i) {
    auto& q = out[i];
    q.x = epoch[i].x;
    q.y = epoch[i].y;
    q.z = epoch[i].z;
    q.residual = static_cast<float>(r.field.residual[i]);
    q.sigma = static_cast<float>(r.field.sigma[i]);
    q.significant = r.field.significant[i];
    q.region = r.regions.region[i];
  }
  // The origin and the CRS in the header too (not only in -json), so the file keeps its frame on
  // its own.
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(out, blob);
  const std::string crs_line = crs_wkt.empty() ? "" : pcl_ls3d::io::pcdCrsLine(crs_wkt) + "\n";
  return pcl_ls3d::io::savePcdBinaryWithOrigin(path, blob, origin, crs_line, error);
}

/// The map's line on heights converted to the plan unit; empty when none were.
std::string
heightsNote(const pcl_ls3d::HeightUnits& h, const std::string& crs_wkt)
{
  if (!h.converts())
    return "";
  std::string unit = pcl_ls3d::maps::crsLinearUnitName(crs_wkt);
  unit = unit.empty() ? "the plan unit" : unit;
  char line[160];
  if (h.target == h.source)
    std::snprintf(line, sizeof line, "heights converted to %s (x %.7g) before matching", unit.c_str(),
                  h.target);
  else
    std::snprintf(line, sizeof line,
                  "heights converted to %s (reference x %.7g, epoch x %.7g) before matching", unit.c_str(),
                  h.target, h.source);
  return line;
}

/// PREFIX.png (.pdf, .svg) and PREFIX.tif of the residuals (deformation/deformation_map.h).
bool
writeMap(const std::string& prefix, const std::vector<Eigen::Vector3d>& points,
         const def::DeformationResult& r, const Eigen::Vector3d& origin, const std::string& crs_wkt,
         const std::string& reference_path, const std::string& epoch_path, double k, bool lod95, double cell,
         const std::string& heights_note, bool overwrite, pcl_ls3d::maps::MapFormat format,
         std::string& error)
{
  def::DeformationMapSettings ms;
  ms.title = "Deformation: " + std::filesystem::path(epoch_path).filename().string() + " against " +
             std::filesystem::path(reference_path).filename().string();
  ms.origin = origin;
  ms.crs_wkt = crs_wkt;
  ms.k = k;
  ms.lod95 = lod95;
  ms.cell = cell;
  ms.heights_note = heights_note;
  return def::writeDeformationMap(prefix, def::makeDeformationMap(points, r, ms), crs_wkt, overwrite, error,
                                  format);
}

/// Everything the command line asks for, checked before any input is read.
struct Options
{
  std::string reference_path, epoch_path, rule_text = "lzd", out_path, json_path, map_prefix;
  std::string picture_path, tif_path, crs_wkt;  ///< the map's files; the -crs CRS (empty: none)
  pcl_ls3d::maps::MapFormat map_format = pcl_ls3d::maps::MapFormat::PNG;
  bool overwrite = false, lod95 = false;
  double map_cell = 0.0;
  def::DeformationSettings settings;
};

/// The numeric options as given (or their defaults), before they enter the settings.
struct NumericOptions
{
  int subsets = 0, min_region = 10, refine = 10, max_iter = 30;
  long long matching_points = 50000;
  double k = 3.0, contamination = 0.5, max_dist = -1.0, seed = 1.0, grow_k = 2.0;
};

/// The numeric options, each in its range (-map_cell straight into the options).
bool
parseNumbers(int argc, char** argv, NumericOptions& n, double& map_cell, std::string& why)
{
  using pcl_ls3d::tools::integerOption;
  using pcl_ls3d::tools::numberOption;
  return integerOption(argc, argv, "-subsets", n.subsets, why, 1, 10000000) &&
         integerOption(argc, argv, "-min_region", n.min_region, why, 1, 1000000000) &&
         integerOption(argc, argv, "-refine", n.refine, why, 0, 100) &&
         integerOption(argc, argv, "-max_iter", n.max_iter, why, 1, 100000) &&
         numberOption(argc, argv, "-grow_k", n.grow_k, why, 0.0, 1e6) &&
         integerOption(argc, argv, "-matching_points", n.matching_points, why, 0, 1000000000000LL) &&
         numberOption(argc, argv, "-seed", n.seed, why, 0, 4294967295.0) &&
         numberOption(argc, argv, "-k", n.k, why, 1e-6, 1e6) &&
         numberOption(argc, argv, "-contamination", n.contamination, why, 1e-6, 0.5) &&
         numberOption(argc, argv, "-max_dist", n.max_dist, why, 1e-12) &&
         numberOption(argc, argv, "-map_cell", map_cell, why, 1e-12);
}

/// -lod95 against -k and -grow_k: a conflict is an error; a default -grow_k that cannot grow
/// the regions a warning.
bool
checkDetectionThresholds(int argc, char** argv, bool lod95, const NumericOptions& n, std::string& why)
{
  if (!optionConflict(argc, argv, lod95, n.k, n.grow_k, why))
    return false;
  if (!pcl_ls3d::tools::optionValue(argc, argv, "-grow_k") && n.grow_k >= (lod95 ? kLod95Factor : n.k))
    print_warn("Warning: %s %g is not above the default -grow_k %g: the regions do not grow (give -grow_k "
               "below it, or 0)\n",
               lod95 ? "-lod95's threshold" : "-k", lod95 ? kLod95Factor : n.k, n.grow_k);
  return true;
}

/// The robust matching's settings from the model and the numbers.
void
applyMatchingSettings(const NumericOptions& n, pcl_ls3d::ParameterModel model,
                      pcl_ls3d::RobustMatchingSettings& m)
{
  m.adjustment.setParameterModel(model);
  m.subsets = n.subsets;
  m.contamination = n.contamination;
  m.seed = static_cast<std::uint32_t>(n.seed);
  if (model == pcl_ls3d::ParameterModel::SIMILARITY_7)
    m.sample_size = 8;
  else if (model == pcl_ls3d::ParameterModel::TRANSLATION_3)
    m.sample_size = 4;
  if (n.max_dist > 0.0)
    m.adjustment.max_correspondence_distance = n.max_dist;
  m.adjustment.max_iterations = n.max_iter;
}

/// -params, -subsets, ... into the deformation settings; false with the reason.
bool
parseSettings(int argc, char** argv, Options& o, std::string& why)
{
  std::string estimator_text = "mm";
  NumericOptions n;
  parse_argument(argc, argv, "-estimator", estimator_text);
  parse_argument(argc, argv, "-rule", o.rule_text);
  pcl_ls3d::ParameterModel model = pcl_ls3d::ParameterModel::RIGID_6;
  if (!pcl_ls3d::tools::parameterModelOption(argc, argv, {"6", "7", "3"}, model, why) ||
      !parseNumbers(argc, argv, n, o.map_cell, why))
    return false;
  o.lod95 = find_switch(argc, argv, "-lod95");
  if (!checkDetectionThresholds(argc, argv, o.lod95, n, why))
    return false;
  def::DeformationSettings& settings = o.settings;
  if (!pcl_ls3d::parseRobustMethod(estimator_text, settings.matching.method))
    return (why = "unknown -estimator " + estimator_text + " (mm, lms, md, m, huber, zuo, ls)"), false;
  if (!pcl_ls3d::parseConjugateRuleType(o.rule_text, settings.rule) ||
      settings.rule == pcl_ls3d::ConjugateRuleType::ICP)
    return (why = "unknown -rule " + o.rule_text + " (lzd or lnd)"), false;
  applyMatchingSettings(n, model, settings.matching);
  settings.residuals.k = n.k;
  if (o.lod95)
    settings.residuals.rule = def::DetectionRule::LOD95;
  settings.regions.min_points = static_cast<std::size_t>(n.min_region);
  settings.regions.grow_k = n.grow_k;
  settings.refinement.max_rounds = n.refine;
  // A model the user named is the model: rigid or nothing. The default may fall back.
  settings.translation_when_undetermined = pcl_ls3d::tools::optionValue(argc, argv, "-params") == nullptr;
  settings.matching_points = static_cast<std::size_t>(n.matching_points);
  if (!settings.isValid(&why))
    return (why = "invalid settings: " + why), false;
  return true;
}

/// Inputs, settings and outputs (-o, -json, -map, -crs), all refused before any file is read.
bool
parseOptions(int argc, char** argv, Options& o, std::string& why)
{
  static const std::set<std::string> valued = {
      "-estimator", "-rule",     "-params",          "-subsets",   "-contamination",
      "-seed",      "-k",        "-min_region",      "-grow_k",    "-refine",
      "-max_iter",  "-max_dist", "-matching_points", "-o",         "-json",
      "-map",       "-crs",      "-map_cell",        "-map_format"};
  std::vector<std::string> files;
  if (!pcl_ls3d::tools::splitArguments(argc, argv, 1, valued, {"-overwrite", "-lod95"}, files, why))
    return false;
  if (files.size() != 2)
    return (why = "expected exactly two input files, REFERENCE and EPOCH (see -h)"), false;
  o.reference_path = files[0];
  o.epoch_path = files[1];
  o.overwrite = find_switch(argc, argv, "-overwrite");
  std::string crs_text;
  parse_argument(argc, argv, "-o", o.out_path);
  parse_argument(argc, argv, "-json", o.json_path);
  parse_argument(argc, argv, "-map", o.map_prefix);
  parse_argument(argc, argv, "-crs", crs_text);
  std::string format_text;
  if (parse_argument(argc, argv, "-map_format", format_text) >= 0 &&
      !pcl_ls3d::maps::parseMapFormat(format_text, o.map_format))
    return (why = "-map_format takes png, pdf or svg, not '" + format_text + "'"), false;
  if (!format_text.empty() && o.map_prefix.empty())
    return (why = "-map_format needs -map PREFIX (the map it formats)"), false;
  if (!parseSettings(argc, argv, o, why))
    return false;
  if (!crs_text.empty() && (o.crs_wkt = pcl_ls3d::maps::crsFromUserInput(crs_text, &why)).empty())
    return (why = "invalid -crs " + crs_text + ": " + why), false;
  o.picture_path = o.map_prefix.empty() ? "" : o.map_prefix + pcl_ls3d::maps::mapExtension(o.map_format);
  o.tif_path = o.map_prefix.empty() ? "" : o.map_prefix + ".tif";
  for (const std::string& out : {o.out_path, o.json_path, o.picture_path, o.tif_path})
    if (!pcl_ls3d::tools::checkOutputFile(out, {o.reference_path, o.epoch_path}, o.overwrite, why))
      return false;
  if (!o.out_path.empty() && pcl_ls3d::io::isSameFile(o.out_path, o.json_path))
    return (why = "-o and -json name the same file"), false;
  const std::string ext = pcl_ls3d::io::fileExtension(o.out_path);
  if (!o.out_path.empty() && ext != "pcd" && ext != "xyz" && ext != "txt")
    return (why = "-o writes .pcd, .xyz or .txt, not ." + ext), false;
  return true;
}

/// The two epochs (io::loadCloudPair): the reference is the pair's target, loaded first; the
/// epoch its source, in the reference's local origin; heights in the plan unit around
/// working_origin.
struct Epochs : pcl_ls3d::io::CloudPair
{
  std::vector<Eigen::Vector3d> points;  ///< the epoch's points, local, in double
  double load_ms = 0.0;
};

bool
loadEpochs(const Options& o, Epochs& e, std::string& error)
{
  TicToc tt;
  tt.tic();
  if (!pcl_ls3d::io::loadCloudPair(o.reference_path, o.epoch_path, e, error, o.crs_wkt))
    return false;
  pcl_ls3d::tools::printPairNotes(e);
  e.load_ms = tt.toc();
  print_info("Loaded reference %s (%zu points) and epoch %s (%zu points), local origin (%.3f, %.3f, %.3f) in "
             "%.0f ms\n",
             o.reference_path.c_str(), e.target->size(), o.epoch_path.c_str(), e.source->size(),
             e.target_info.origin.x(), e.target_info.origin.y(), e.target_info.origin.z(), e.load_ms);
  if (e.target->size() < 3)
    return (error = "the reference has fewer than 3 points"), false;
  e.points.resize(e.source->size());
  for (std::size_t i = 0; i < e.source->size(); ++i)
    e.points[i] = (*e.source)[i].getVector3fMap().cast<double>();
  return true;
}

/// Robust matching of the epoch onto the reference, then the residual field and its regions.
bool
analyse(const Options& o, const Epochs& e, def::DeformationResult& result, double& run_ms, std::string& why)
{
  TicToc tt;
  tt.tic();
  pcl::search::KdTree<pcl_ls3d::PointLiDAR>::Ptr tree(
      new pcl_ls3d::search::FlannKdTree<pcl_ls3d::PointLiDAR>);
  tree->setInputCloud(e.target);
  const pcl_ls3d::PclTargetSurface<pcl_ls3d::PointLiDAR> surface(e.target, tree);
  const pcl_ls3d::ConjugateRule::Ptr rule = pcl_ls3d::makeConjugateRule(o.settings.rule);
  if (!rule->prepare(surface, &why))
    return (why = "the reference cannot be used with rule " + o.rule_text + ": " + why), false;
  {  // the library's own PCL_ERROR would be a second error line: the report's message is printed
    const auto verbosity = getVerbosityLevel();
    setVerbosityLevel(L_ALWAYS);
    result = def::analyseDeformation(e.points, surface, *rule, o.settings);
    setVerbosityLevel(verbosity);
  }
  run_ms = tt.toc();
  const pcl_ls3d::RobustMatchingReport& mr = result.matching;
  if (!result.ok()) {
    why = std::string("robust matching failed: ") + pcl_ls3d::terminationTypeToString(mr.termination) + ": " +
          mr.message;
    // A model named with -params that the surface does not determine: say what would do.
    if (!o.settings.translation_when_undetermined &&
        def::rotationsUndetermined(result, o.settings.matching.adjustment))
      why += " (-params 3, or no -params, estimates the translation alone)";
    return false;
  }
  return true;
}

/// Where the data are: the epoch's centroid (input coordinates) and the shift the
/// transformation gives it.
struct CentroidShift
{
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), shift = Eigen::Vector3d::Zero();
};

CentroidShift
centroidShift(const Epochs& e, const Eigen::Matrix4d& local_transformation)
{
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::size_t finite = 0;
  for (const Eigen::Vector3d& p : e.points)
    if (p.allFinite()) {
      centroid += p;
      ++finite;
    }
  centroid /= static_cast<double>(std::max<std::size_t>(finite, 1));
  CentroidShift c;
  c.shift = (local_transformation * centroid.homogeneous()).head<3>() - centroid;
  c.centroid = e.heights.sourceToFile(centroid + e.working_origin);
  return c;
}

/// The result on the console: transformation, parameters, the start's choice, the regions.
void
printResult(const Epochs& e, const def::DeformationResult& result, const CentroidShift& c, double run_ms)
{
  const pcl_ls3d::RobustMatchingReport& mr = result.matching;
  const pcl_ls3d::AdjustmentReport& a = mr.adjustment;
  const Eigen::Vector3d& origin = e.working_origin;
  print_info("%s\n", mr.brief().c_str());
  if (!mr.message.empty())
    print_info("  %s\n", mr.message.c_str());
  if (!result.model_note.empty())
    print_warn("Note: %s\n", result.model_note.c_str());
  pcl_ls3d::tools::printTransformation(
      "Transformation (EPOCH -> REFERENCE, input coordinates):",
      e.heights.toFiles(pcl_ls3d::localToGlobal(a.transformation, origin, origin)));
  print_info("Shift of the epoch's centroid (%.3f, %.3f, %.3f): (%+.4f, %+.4f, %+.4f)%s\n", c.centroid.x(),
             c.centroid.y(), c.centroid.z(), c.shift.x(), c.shift.y(), c.shift.z(),
             e.heights.converts() ? " (the shift with its height in the plan unit)" : "");
  printParameters(a, a.local_origin_source + origin, a.local_origin_target + origin, e.heights.converts());
  if (!result.start_choice.candidates.empty()) {
    print_info("Fits compared by the scatter of their stable part:");
    for (const auto& candidate : result.start_choice.candidates)
      print_info(" %s %.4g", candidate.name.c_str(), candidate.scatter);
    print_info("; kept: %s\n", result.start_choice.chosen.c_str());
  }
  const def::RegionAnalysis& reg = result.regions;
  print_info("Robust scale %.4g; %zu of %zu epoch points observed, %zu significant; %zu regions, %zu noise "
             "clusters; %.2f %% of the area deformed\n",
             mr.scale, result.field.observed, e.source->size(), result.field.significant_count,
             reg.regions.size(), reg.noise.size(), reg.percent_deformed);
  // A robust estimator takes the larger part to be stable; near half, the data cannot say which.
  if (reg.percent_deformed > kNearHalfPercent)
    print_warn("Warning: %.1f %% of the observed area differs: the part taken as stable is only the larger "
               "one; check on the map which part really moved\n",
               reg.percent_deformed);
  for (std::size_t i = 0; i < std::min<std::size_t>(reg.regions.size(), 10); ++i) {
    const auto& r = reg.regions[i];
    print_info("  region %d: %s, %zu points, area %.4g, mean %+.4g (min %+.4g, max %+.4g), volume %+.4g\n",
               r.id, r.sign > 0 ? "up/out" : "down/in", r.points, r.area, r.mean, r.min, r.max, r.volume);
  }
  print_info("Timings: load %.0f ms, matching and residuals %.0f ms\n", e.load_ms, run_ms);
}

/// The fits that competed for the start (deformation/start_choice.h) and the one chosen.
nlohmann::json
startChoiceJson(const def::StartChoice& choice, double block_support)
{
  nlohmann::json scores = nlohmann::json::object(), usable = nlohmann::json::object();
  for (const auto& candidate : choice.candidates) {
    scores[candidate.name] =
        finiteOrNull(candidate.scatter);  // null: refused, or its regions are the majority
    usable[candidate.name] = candidate.usable;
  }
  return {{"chosen", choice.chosen},
          {"stable_part_scatter", scores},
          {"usable", usable},
          {"block_support", block_support}};
}

nlohmann::json
regionsJson(const std::vector<def::DeformationRegion>& regions, const Eigen::Vector3d& origin,
            const pcl_ls3d::HeightUnits& heights)
{
  nlohmann::json out = nlohmann::json::array();
  for (const auto& r : regions)
    out.push_back(regionJson(r, origin, heights));
  return out;
}

/// The -json report.
nlohmann::json
reportJson(const Options& o, const Epochs& e, const def::DeformationResult& result, const CentroidShift& c,
           double run_ms)
{
  const pcl_ls3d::RobustMatchingReport& mr = result.matching;
  const pcl_ls3d::AdjustmentReport& a = mr.adjustment;
  const Eigen::Vector3d& origin = e.working_origin;
  const Eigen::Vector3d o_s = a.local_origin_source + origin, o_t = a.local_origin_target + origin;
  nlohmann::json j;
  j["transformation"] =
      matrixJson(e.heights.toFiles(pcl_ls3d::localToGlobal(a.transformation, origin, origin)));
  if (e.heights.converts())
    j["heights"] = pcl_ls3d::heightUnitsJson(e.heights);
  j["converged"] = mr.termination == pcl_ls3d::TerminationType::CONVERGED;
  j["termination"] = pcl_ls3d::terminationTypeToString(mr.termination);
  j["message"] = mr.message;
  const auto& names = pcl_ls3d::similarityParameterNames();
  nlohmann::json p, s;
  for (std::size_t i = 0; i < 7; ++i) {
    p[names[i]] = a.parameters[static_cast<int>(i)];
    s[names[i]] = finiteOrNull(a.sigmas[static_cast<int>(i)]);
  }
  j["parameters"] = p;
  j["parameters_note"] = "reduced frame, input coordinates (heights in the plan unit when 'heights' "
                         "says so): x_t - local_origin_target = t + m R (x_s - local_origin_source); "
                         "local_origin is the origin of the -o cloud's coordinates";
  j["local_origin_source"] = {o_s.x(), o_s.y(), o_s.z()};
  j["local_origin_target"] = {o_t.x(), o_t.y(), o_t.z()};
  j["sigmas"] = s;
  j["estimator"] = mr.estimator;
  const pcl_ls3d::AdjustmentSettings& model = result.model_note.empty()
                                                  ? o.settings.matching.adjustment
                                                  : def::translationAlone(o.settings.matching.adjustment);
  j["params"] = pcl_ls3d::freeParameterCount(model.apriori_weights);
  if (!result.model_note.empty())
    j["model_note"] = result.model_note;
  j["method"] = pcl_ls3d::toString(mr.method);
  j["rule"] = o.rule_text;
  j["scale"] = mr.scale;
  j["high_breakdown_scale"] = mr.high_breakdown_scale;
  j["neighbour_noise"] = mr.neighbour_noise;
  j["subsets"] = mr.subsets_drawn;
  j["rounds"] = mr.rounds;
  j["iterations"] = mr.iterations;
  if (!result.start_choice.candidates.empty())
    j["start_choice"] = startChoiceJson(result.start_choice, mr.block_support);
  j["stable_refinement"] = {{"rounds", result.refinement.rounds},
                            {"points_left_out", result.refinement.left_out},
                            {"stopped", result.refinement.stopped}};
  j["sigma0"] = a.sigma0;
  j["significance"] = def::toString(o.settings.residuals.rule);
  j["k"] = o.settings.residuals.k;
  j["points"] = e.source->size();
  j["points_observed"] = result.field.observed;
  j["points_significant"] = result.field.significant_count;
  j["epoch_centroid"] = {c.centroid.x(), c.centroid.y(), c.centroid.z()};
  j["centroid_shift"] = {c.shift.x(), c.shift.y(), c.shift.z()};
  const def::RegionAnalysis& reg = result.regions;
  j["percent_deformed"] = reg.percent_deformed;
  j["stable_part_ambiguous"] = reg.percent_deformed > kNearHalfPercent;
  j["matching_points"] = a.source_points;
  j["area_observed"] = reg.area_observed;
  j["area_deformed"] = reg.area_deformed;
  j["spacing"] = reg.spacing;
  j["regions"] = regionsJson(reg.regions, origin, e.heights);
  j["noise"] = regionsJson(reg.noise, origin, e.heights);
  j["local_origin"] = {e.target_info.origin.x(), e.target_info.origin.y(), e.target_info.origin.z()};
  j["timings_ms"] = {{"load", e.load_ms}, {"deformation", run_ms}};
  return j;
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
  Epochs e;
  def::DeformationResult result;
  double run_ms = 0.0;
  std::string error;
  if (!parseOptions(argc, argv, o, error) || !loadEpochs(o, e, error) ||
      !analyse(o, e, result, run_ms, error))
    return fail(error), 1;
  const pcl_ls3d::RobustMatchingReport& mr = result.matching;
  const CentroidShift centroid = centroidShift(e, mr.adjustment.transformation);
  printResult(e, result, centroid, run_ms);

  // -crs, else the CRS the reference declares: the map's and the residual file's.
  const std::string crs_wkt = o.crs_wkt.empty() ? pcl_ls3d::maps::crsOfFile(e.target_info) : o.crs_wkt;
  if (!o.out_path.empty()) {
    Cloud epoch_in_file_units = *e.source;  // in the reference's height unit, as its CRS
    pcl_ls3d::heightsToFile(epoch_in_file_units, e.heights.target, e.heights.target,
                            e.target_info.origin.z());
    if (!writeResiduals(o.out_path, epoch_in_file_units, result, e.target_info.origin, crs_wkt, error))
      return fail(error), 1;
    print_info("Wrote %s\n", o.out_path.c_str());
  }
  if (!o.map_prefix.empty()) {
    if (!writeMap(o.map_prefix, e.points, result, e.working_origin, crs_wkt, o.reference_path, o.epoch_path,
                  o.settings.residuals.k, o.lod95, o.map_cell, heightsNote(e.heights, crs_wkt), o.overwrite,
                  o.map_format, error))
      return fail(error), 1;
    print_info("Wrote %s and %s%s\n", o.picture_path.c_str(), o.tif_path.c_str(),
               crs_wkt.empty() ? " (no coordinate reference known: use -crs)" : "");
  }
  if (!o.json_path.empty() &&
      !pcl_ls3d::tools::writeJsonFile(o.json_path, reportJson(o, e, result, centroid, run_ms)))
    return fail("cannot write " + o.json_path), 1;
  if (mr.termination != pcl_ls3d::TerminationType::CONVERGED) {
    print_warn("Warning: the matching ended %s, not CONVERGED: the transformation and the residuals "
               "are the last iterate's (exit 3)\n",
               pcl_ls3d::terminationTypeToString(mr.termination));
    return 3;
  }
  return 0;
}
