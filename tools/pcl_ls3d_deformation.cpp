// pcl_ls3d_deformation: robust matching of EPOCH onto REFERENCE and the map of what moved
// (Li et al. 2001; issue 9).
#include "tool_arguments.h"
#include "tool_output.h"

#include <pcl_ls3d/common/similarity_transform.h>
#include <pcl_ls3d/deformation/deformation_analysis.h>
#include <pcl_ls3d/deformation/deformation_map.h>
#include <pcl_ls3d/deformation/point_residual.h>
#include <pcl_ls3d/io/cloud_io.h>
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
  print_info(
      "Local deformation between two epochs of a surface: robust matching of EPOCH onto REFERENCE\n"
      "(the transformation of the stable part, no control points; up to half the surface may have\n"
      "moved), then the residual of every epoch point, its sigma, significance and the connected\n"
      "deformed regions (Li, Xu, Chen & Tsai 2001).\n\n"
      "Usage: %s REFERENCE EPOCH [options]\n"
      "  REFERENCE, EPOCH     .las .pcd .ply .xyz/.txt (a gridded DEM as x y z text works too;\n"
      "                       the reference is loaded first, the epoch uses its local origin)\n"
      "  -estimator NAME      mm (default: LTS start + Tukey M-step, high breakdown and 95 %%\n"
      "                       efficiency), lms (Li: LMS subsets then M), md (Li's M-D), m (Tukey on\n"
      "                       MAD), huber, zuo, ls (plain least squares). mm and lms also fit from\n"
      "                       a block start and keep the fit whose stable part scatters least\n"
      "  -rule lzd|lnd        residuals along z (LHD, default) or along the surface normal\n"
      "  -params 6|7|3        rigid (default), similarity, translation\n"
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
      "                       origin in the header and the JSON) residual sigma significant\n"
      "                       region; .xyz/.txt:\n"
      "                       the same as text with full file coordinates\n"
      "  -json REPORT         transformation (4x4 row-major, EPOCH -> REFERENCE, input\n"
      "                       coordinates), converged, parameters and sigmas (reduced frame about\n"
      "                       local_origin_source / local_origin_target), estimator, scale,\n"
      "                       subsets, percent_deformed, regions\n"
      "  -map PREFIX          PREFIX.png (residual map, diverging colour bar, significant regions\n"
      "                       outlined) and PREFIX.tif (float32 GeoTIFF of the residuals, NaN\n"
      "                       where no point has one, with the CRS of -crs or the reference's LAS)\n"
      "  -map_cell C          map cell edge (default 1.5 point spacings; irregular airborne data:\n"
      "                       about 2.5 spacings, so that most cells hold points)\n"
      "  -crs CRS             coordinate reference of the inputs for the GeoTIFF (EPSG:26917, a\n"
      "                       PROJ string or WKT; default: the reference's LAS CRS, if any)\n"
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
  std::snprintf(buf, sizeof(buf), "-grow_k %g must be below %s (%g): regions grow into weaker neighbours "
                "(-grow_k 0: off)", grow_k, lod95 ? "-lod95's threshold" : "-k", detection);
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
printParameters(const pcl_ls3d::AdjustmentReport& a, const Eigen::Vector3d& o_s, const Eigen::Vector3d& o_t)
{
  print_info("Parameters in the reduced frame x_ref - o_t = t + m R (x_epoch - o_s), input coordinates,\n"
             "  o_s (%.4f, %.4f, %.4f), o_t (%.4f, %.4f, %.4f): t is the shift beyond o_t - o_s\n ",
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

nlohmann::json
finiteOrNull(double v)
{
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json
matrixJson(const Eigen::Matrix4d& T)
{
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r)
    rows.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
  return rows;
}

nlohmann::json
regionJson(const def::DeformationRegion& r, const Eigen::Vector3d& origin)
{
  const Eigen::Vector3d c = r.centroid + origin, lo = r.box_min + origin, hi = r.box_max + origin;
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
               const Eigen::Vector3d& origin, std::string& error)
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
  // The origin in the header too (not only in -json), so the file keeps its frame on its own.
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(out, blob);
  return pcl_ls3d::io::savePcdBinaryWithOrigin(path, blob, origin, "", error);
}


/// PREFIX.png and PREFIX.tif of the residuals (deformation/deformation_map.h).
bool
writeMap(const std::string& prefix, const std::vector<Eigen::Vector3d>& points, const def::DeformationResult& r,
         const Eigen::Vector3d& origin, const std::string& crs_wkt, const std::string& reference_path,
         const std::string& epoch_path, double k, bool lod95, double cell, bool overwrite, std::string& error)
{
  def::DeformationMapSettings ms;
  ms.title = "Deformation: " + std::filesystem::path(epoch_path).filename().string() + " against " +
             std::filesystem::path(reference_path).filename().string();
  ms.origin = origin;
  ms.crs_wkt = crs_wkt;
  ms.k = k;
  ms.lod95 = lod95;
  ms.cell = cell;
  return def::writeDeformationMap(prefix, def::makeDeformationMap(points, r, ms), crs_wkt, overwrite, error);
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
  static const std::set<std::string> valued = {"-estimator", "-rule", "-params", "-subsets",
                                               "-contamination", "-seed", "-k", "-min_region", "-grow_k", "-refine",
                                               "-max_iter", "-max_dist", "-matching_points", "-o", "-json",
                                               "-map", "-crs", "-map_cell"};
  std::vector<std::string> files;
  std::string why;
  if (!pcl_ls3d::tools::splitArguments(argc, argv, 1, valued, {"-overwrite", "-lod95"}, files, why))
    return fail(why), 1;
  if (files.size() != 2)
    return fail("expected exactly two input files, REFERENCE and EPOCH (see -h)"), 1;
  const std::string reference_path = files[0], epoch_path = files[1];

  std::string estimator_text = "mm", rule_text = "lzd", out_path, json_path, map_prefix, crs_text;
  int params = 6, subsets = 0, min_region = 10, refine = 10, max_iter = 30;
  long long matching_points = 50000;
  double k = 3.0, contamination = 0.5, max_dist = -1.0, seed = 1.0, map_cell = 0.0, grow_k = 2.0;
  const bool overwrite = find_switch(argc, argv, "-overwrite");
  parse_argument(argc, argv, "-estimator", estimator_text);
  parse_argument(argc, argv, "-rule", rule_text);
  parse_argument(argc, argv, "-o", out_path);
  parse_argument(argc, argv, "-json", json_path);
  parse_argument(argc, argv, "-map", map_prefix);
  parse_argument(argc, argv, "-crs", crs_text);
  using pcl_ls3d::tools::integerOption;
  using pcl_ls3d::tools::numberOption;
  using pcl_ls3d::tools::optionValue;
  if (!integerOption(argc, argv, "-params", params, why, 3, 7) || (params != 3 && params != 6 && params != 7))
    return fail(std::string("-params expects 6, 7 or 3, got '") + optionValue(argc, argv, "-params") + "'"), 1;
  if (!integerOption(argc, argv, "-subsets", subsets, why, 1, 10000000) ||
      !integerOption(argc, argv, "-min_region", min_region, why, 1, 1000000000) ||
      !integerOption(argc, argv, "-refine", refine, why, 0, 100) ||
      !integerOption(argc, argv, "-max_iter", max_iter, why, 1, 100000) ||
      !numberOption(argc, argv, "-grow_k", grow_k, why, 0.0, 1e6) ||
      !integerOption(argc, argv, "-matching_points", matching_points, why, 0, 1000000000000LL) ||
      !numberOption(argc, argv, "-seed", seed, why, 0, 4294967295.0) ||
      !numberOption(argc, argv, "-k", k, why, 1e-6, 1e6) ||
      !numberOption(argc, argv, "-contamination", contamination, why, 1e-6, 0.5) ||
      !numberOption(argc, argv, "-max_dist", max_dist, why, 1e-12) ||
      !numberOption(argc, argv, "-map_cell", map_cell, why, 1e-12))
    return fail(why), 1;
  const bool lod95 = find_switch(argc, argv, "-lod95");
  if (!optionConflict(argc, argv, lod95, k, grow_k, why))
    return fail(why), 1;
  if (!optionValue(argc, argv, "-grow_k") && grow_k >= (lod95 ? kLod95Factor : k))
    print_warn("Warning: %s %g is not above the default -grow_k %g: the regions do not grow (give -grow_k "
               "below it, or 0)\n", lod95 ? "-lod95's threshold" : "-k", lod95 ? kLod95Factor : k, grow_k);

  def::DeformationSettings settings;
  pcl_ls3d::RobustMatchingSettings& m = settings.matching;
  if (!pcl_ls3d::parseRobustMethod(estimator_text, m.method))
    return fail("unknown -estimator " + estimator_text + " (mm, lms, md, m, huber, zuo, ls)"), 1;
  if (!pcl_ls3d::parseConjugateRuleType(rule_text, settings.rule) ||
      settings.rule == pcl_ls3d::ConjugateRuleType::ICP)
    return fail("unknown -rule " + rule_text + " (lzd or lnd)"), 1;
  switch (params) {
  case 7: m.adjustment.setParameterModel(pcl_ls3d::ParameterModel::SIMILARITY_7); break;
  case 6: m.adjustment.setParameterModel(pcl_ls3d::ParameterModel::RIGID_6); break;
  case 3: m.adjustment.setParameterModel(pcl_ls3d::ParameterModel::TRANSLATION_3); break;
  }
  m.subsets = subsets;
  m.contamination = contamination;
  m.seed = static_cast<std::uint32_t>(seed);
  if (params == 7)
    m.sample_size = 8;
  else if (params == 3)
    m.sample_size = 4;
  if (max_dist > 0.0)
    m.adjustment.max_correspondence_distance = max_dist;
  m.adjustment.max_iterations = max_iter;
  settings.residuals.k = k;
  if (lod95)
    settings.residuals.rule = def::DetectionRule::LOD95;
  settings.regions.min_points = static_cast<std::size_t>(min_region);
  settings.regions.grow_k = grow_k;
  settings.refinement.max_rounds = refine;
  settings.matching_points = static_cast<std::size_t>(matching_points);
  if (!settings.isValid(&why))
    return fail("invalid settings: " + why), 1;

  std::string crs_wkt;
  if (!crs_text.empty() && (crs_wkt = pcl_ls3d::maps::crsFromUserInput(crs_text, &why)).empty())
    return fail("invalid -crs " + crs_text + ": " + why), 1;
  const std::string png_path = map_prefix.empty() ? "" : map_prefix + ".png";
  const std::string tif_path = map_prefix.empty() ? "" : map_prefix + ".tif";
  for (const std::string& out : {out_path, json_path, png_path, tif_path})
    if (!pcl_ls3d::tools::checkOutputFile(out, {reference_path, epoch_path}, overwrite, why))
      return fail(why), 1;
  if (!out_path.empty() && pcl_ls3d::io::isSameFile(out_path, json_path))
    return fail("-o and -json name the same file"), 1;
  if (!out_path.empty()) {
    const std::string ext = pcl_ls3d::io::fileExtension(out_path);
    if (ext != "pcd" && ext != "xyz" && ext != "txt")
      return fail("-o writes .pcd, .xyz or .txt, not ." + ext), 1;
  }

  // Load: reference first, the epoch in the reference's local origin.
  TicToc tt;
  tt.tic();
  Cloud::Ptr reference(new Cloud), epoch(new Cloud);
  pcl_ls3d::io::CloudInfo rinfo, einfo;
  std::string error;
  if (!pcl_ls3d::io::loadCloud(reference_path, *reference, rinfo, error))
    return fail(error), 1;
  pcl_ls3d::io::LoadOptions eopt;
  eopt.use_origin = true;
  eopt.origin = rinfo.origin;
  if (!pcl_ls3d::io::loadCloud(epoch_path, *epoch, einfo, error, eopt))
    return fail(error), 1;
  const double t_load = tt.toc();
  print_info("Loaded reference %s (%zu points) and epoch %s (%zu points), local origin (%.3f, %.3f, %.3f) in %.0f ms\n",
             reference_path.c_str(), reference->size(), epoch_path.c_str(), epoch->size(),
             rinfo.origin.x(), rinfo.origin.y(), rinfo.origin.z(), t_load);
  if (reference->size() < 3)
    return fail("the reference has fewer than 3 points"), 1;

  // Robust matching and the residual field.
  tt.tic();
  pcl::search::KdTree<pcl_ls3d::PointLiDAR>::Ptr tree(
      new pcl_ls3d::search::FlannKdTree<pcl_ls3d::PointLiDAR>);
  tree->setInputCloud(reference);
  const pcl_ls3d::PclTargetSurface<pcl_ls3d::PointLiDAR> surface(reference, tree);
  const pcl_ls3d::ConjugateRule::Ptr rule = pcl_ls3d::makeConjugateRule(settings.rule);
  if (!rule->prepare(surface, &why))
    return fail("the reference cannot be used with rule " + rule_text + ": " + why), 1;
  std::vector<Eigen::Vector3d> points(epoch->size());
  for (std::size_t i = 0; i < epoch->size(); ++i)
    points[i] = (*epoch)[i].getVector3fMap().cast<double>();
  def::DeformationResult result;
  {  // the library's own PCL_ERROR would be a second error line: the report's message is printed
    const auto verbosity = getVerbosityLevel();
    setVerbosityLevel(L_ALWAYS);
    result = def::analyseDeformation(points, surface, *rule, settings);
    setVerbosityLevel(verbosity);
  }
  const double t_run = tt.toc();
  const pcl_ls3d::RobustMatchingReport& mr = result.matching;
  if (!result.ok())
    return fail(std::string("robust matching failed: ") + pcl_ls3d::terminationTypeToString(mr.termination) +
                ": " + mr.message), 1;

  const pcl_ls3d::AdjustmentReport& a = mr.adjustment;
  const Eigen::Matrix4d T = pcl_ls3d::localToGlobal(a.transformation, rinfo.origin, rinfo.origin);
  const bool converged = mr.termination == pcl_ls3d::TerminationType::CONVERGED;
  print_info("%s\n", mr.brief().c_str());
  if (!mr.message.empty())
    print_info("  %s\n", mr.message.c_str());
  pcl_ls3d::tools::printTransformation("Transformation (EPOCH -> REFERENCE, input coordinates):", T);
  // What the transformation does where the data are: the shift of the epoch's centroid.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::size_t finite = 0;
  for (const Eigen::Vector3d& p : points)
    if (p.allFinite()) {
      centroid += p;
      ++finite;
    }
  centroid /= static_cast<double>(std::max<std::size_t>(finite, 1));
  const Eigen::Vector3d shift = (a.transformation * centroid.homogeneous()).head<3>() - centroid;
  const Eigen::Vector3d centroid_in = centroid + rinfo.origin;
  print_info("Shift of the epoch's centroid (%.3f, %.3f, %.3f): (%+.4f, %+.4f, %+.4f)\n", centroid_in.x(),
             centroid_in.y(), centroid_in.z(), shift.x(), shift.y(), shift.z());
  const Eigen::Vector3d o_s = a.local_origin_source + rinfo.origin, o_t = a.local_origin_target + rinfo.origin;
  printParameters(a, o_s, o_t);
  if (!result.start_choice.candidates.empty()) {
    print_info("Fits compared by the scatter of their stable part:");
    for (const auto& c : result.start_choice.candidates)
      print_info(" %s %.4g", c.name.c_str(), c.scatter);
    print_info("; kept: %s\n", result.start_choice.chosen.c_str());
  }
  const def::RegionAnalysis& reg = result.regions;
  print_info("Robust scale %.4g; %zu of %zu epoch points observed, %zu significant; %zu regions, %zu noise "
             "clusters; %.2f %% of the area deformed\n",
             mr.scale, result.field.observed, epoch->size(), result.field.significant_count,
             reg.regions.size(), reg.noise.size(), reg.percent_deformed);
  // A robust estimator takes the larger part to be stable; near half, the data cannot say which.
  const bool near_half = reg.percent_deformed > kNearHalfPercent;
  if (near_half)
    print_warn("Warning: %.1f %% of the observed area differs: the part taken as stable is only the larger "
               "one; check on the map which part really moved\n",
               reg.percent_deformed);
  for (std::size_t i = 0; i < std::min<std::size_t>(reg.regions.size(), 10); ++i) {
    const auto& r = reg.regions[i];
    print_info("  region %d: %s, %zu points, area %.4g, mean %+.4g (min %+.4g, max %+.4g), volume %+.4g\n",
               r.id, r.sign > 0 ? "up/out" : "down/in", r.points, r.area, r.mean, r.min, r.max, r.volume);
  }
  print_info("Timings: load %.0f ms, matching and residuals %.0f ms\n", t_load, t_run);

  if (!out_path.empty()) {
    if (!writeResiduals(out_path, *epoch, result, rinfo.origin, error))
      return fail(error), 1;
    print_info("Wrote %s\n", out_path.c_str());
  }
  if (!map_prefix.empty()) {
    if (crs_wkt.empty() && rinfo.format == "las")
      crs_wkt = pcl_ls3d::maps::crsFromLasVlrs(rinfo.las.vlrs);
    if (!writeMap(map_prefix, points, result, rinfo.origin, crs_wkt, reference_path, epoch_path,
                  settings.residuals.k, lod95, map_cell, overwrite, error))
      return fail(error), 1;
    print_info("Wrote %s and %s%s\n", png_path.c_str(), tif_path.c_str(),
               crs_wkt.empty() ? " (no coordinate reference known: use -crs)" : "");
  }
  if (!json_path.empty()) {
    nlohmann::json j;
    j["transformation"] = matrixJson(T);
    j["converged"] = converged;
    j["termination"] = pcl_ls3d::terminationTypeToString(mr.termination);
    j["message"] = mr.message;
    const auto& names = pcl_ls3d::similarityParameterNames();
    nlohmann::json p, s;
    for (std::size_t i = 0; i < 7; ++i) {
      p[names[i]] = a.parameters[static_cast<int>(i)];
      s[names[i]] = finiteOrNull(a.sigmas[static_cast<int>(i)]);
    }
    j["parameters"] = p;
    j["parameters_note"] = "reduced frame, input coordinates: x_t - local_origin_target = t + m R (x_s - "
                           "local_origin_source); local_origin is the origin of the -o cloud's coordinates";
    j["local_origin_source"] = {o_s.x(), o_s.y(), o_s.z()};
    j["local_origin_target"] = {o_t.x(), o_t.y(), o_t.z()};
    j["sigmas"] = s;
    j["estimator"] = mr.estimator;
    j["method"] = pcl_ls3d::toString(mr.method);
    j["rule"] = rule_text;
    j["scale"] = mr.scale;
    j["high_breakdown_scale"] = mr.high_breakdown_scale;
    j["neighbour_noise"] = mr.neighbour_noise;
    j["subsets"] = mr.subsets_drawn;
    j["rounds"] = mr.rounds;
    j["iterations"] = mr.iterations;
    if (!result.start_choice.candidates.empty()) {
      nlohmann::json scores = nlohmann::json::object(), usable = nlohmann::json::object();
      for (const auto& c : result.start_choice.candidates) {
        scores[c.name] = finiteOrNull(c.scatter);  // null: refused, or its regions are the majority
        usable[c.name] = c.usable;
      }
      j["start_choice"] = {{"chosen", result.start_choice.chosen},
                           {"stable_part_scatter", scores},
                           {"usable", usable},
                           {"block_support", mr.block_support}};
    }
    j["stable_refinement"] = {{"rounds", result.refinement.rounds},
                              {"points_left_out", result.refinement.left_out},
                              {"stopped", result.refinement.stopped}};
    j["sigma0"] = a.sigma0;
    j["significance"] = def::toString(settings.residuals.rule);
    j["k"] = settings.residuals.k;
    j["points"] = epoch->size();
    j["points_observed"] = result.field.observed;
    j["points_significant"] = result.field.significant_count;
    j["epoch_centroid"] = {centroid_in.x(), centroid_in.y(), centroid_in.z()};
    j["centroid_shift"] = {shift.x(), shift.y(), shift.z()};
    j["percent_deformed"] = reg.percent_deformed;
    j["stable_part_ambiguous"] = near_half;
    j["matching_points"] = a.source_points;
    j["area_observed"] = reg.area_observed;
    j["area_deformed"] = reg.area_deformed;
    j["spacing"] = reg.spacing;
    nlohmann::json regions = nlohmann::json::array(), noise = nlohmann::json::array();
    for (const auto& r : reg.regions)
      regions.push_back(regionJson(r, rinfo.origin));
    for (const auto& r : reg.noise)
      noise.push_back(regionJson(r, rinfo.origin));
    j["regions"] = regions;
    j["noise"] = noise;
    const Eigen::Vector3d o = rinfo.origin;
    j["local_origin"] = {o.x(), o.y(), o.z()};
    j["timings_ms"] = {{"load", t_load}, {"deformation", t_run}};
    if (!pcl_ls3d::tools::writeJsonFile(json_path, j))
      return fail("cannot write " + json_path), 1;
  }
  if (!converged) {
    print_warn("Warning: the matching ended %s, not CONVERGED: the transformation and the residuals "
               "are the last iterate's (exit 3)\n", pcl_ls3d::terminationTypeToString(mr.termination));
    return 3;
  }
  return 0;
}
