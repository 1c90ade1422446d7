// benchmark_real_pairs: LS3D (LND, LZD, ICP rules, class defaults) against PCL's ICP,
// point-to-plane ICP, GICP and NDT on real pairs from the shared data folder (issue 10, "Fair
// comparison, on real data too"), all in one process:
//  - PCL's bun0 -> bun4 with the ground truth of PCL's PPF registration test;
//  - the simpleICP dragon known-transform triple (dragon1 -> dragon2, dragon1 -> dragon3);
//  - the simpleICP bunny partial-overlap pair (no reference: discrepancy statistics);
//  - IGN LiDAR HD tiles split into flight strips by point-source id (no reference: σ_MAD of the
//    signed normal discrepancies before / after).
// Targets per pair with a reference: LS3D-LND with defaults at least as accurate (mean
// displacement) as the best PCL method and its wall time <= PCL-GICP's.
#include <pcl_ls3d/evaluation/ls3d_method.h>
#include <pcl_ls3d/evaluation/pcl_methods.h>
#include <pcl_ls3d/evaluation/registration_run.h>
#include <pcl_ls3d/evaluation/surface_discrepancy.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/strip_tools.h>
#include <pcl_ls3d/synth/spinning_scan.h>

#include <pcl/common/io.h>
#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/kdtree/kdtree_flann.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

using namespace pcl_ls3d;
using namespace pcl_ls3d::evaluation;

namespace {

using CloudXYZ = pcl::PointCloud<pcl::PointXYZ>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

#ifndef PCL_LS3D_SHARED_DATA_DIR
#define PCL_LS3D_SHARED_DATA_DIR "../shared/data"
#endif

void
printHelp(const char* name)
{
  pcl::console::print_info(
      "Usage: %s [options]\n"
      "  -data DIR        shared data folder (default %s)\n"
      "  -pairs LIST      comma-separated subset of: bun,dragon,bunny,ign,spin (default all;\n"
      "                   spin: a generated spinning-LiDAR pair, needs no data)\n"
      "  -pcl_iter N      iteration limit of the PCL methods (default 200)\n"
      "  -h               this help\n",
      name, PCL_LS3D_SHARED_DATA_DIR);
}

bool
fileExists(const std::string& path)
{
  return std::ifstream(path).good();
}

/// One pair to register: clouds in a common local frame, optional reference, settings.
struct Case
{
  std::string name;
  CloudXYZ::Ptr source, target;
  bool has_truth = false;
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity();
  PclMethodSettings pcl;
  std::string pcl_choice;  ///< why these PCL settings (printed)
  DiscrepancySettings discrepancy;
  bool check_targets = false;
};

/// Median nearest-neighbour distance of up to 2000 points of `cloud` (its point spacing).
double
pointSpacing(const CloudXYZ::ConstPtr& cloud)
{
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(cloud);
  std::vector<double> d;
  const std::size_t step = std::max<std::size_t>(1, cloud->size() / 2000);
  for (std::size_t i = 0; i < cloud->size(); i += step) {
    pcl::Indices k;
    std::vector<float> d2;
    if (tree.nearestKSearch((*cloud)[i], 2, k, d2) == 2)
      d.push_back(std::sqrt(static_cast<double>(d2[1])));
  }
  if (d.empty())
    return kNaN;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

double
diagonal(const CloudXYZ& cloud)
{
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f hi = -lo;
  for (const auto& p : cloud) {
    lo = lo.cwiseMin(p.getVector3fMap());
    hi = hi.cwiseMax(p.getVector3fMap());
  }
  return static_cast<double>((hi - lo).norm());
}

/// PCL settings a user would pick for a close-range object scan: correspondence reach a quarter
/// of the source's diagonal (PCL's own bun0/bun4 test uses 0.05 m on a 0.2 m bunny), NDT voxel
/// 1/20 of it with a quarter-voxel step; everything else as PclMethodSettings.
void
objectSettings(Case& c, int pcl_iter)
{
  const double D = diagonal(*c.source), s = pointSpacing(c.target);
  c.pcl.max_iterations = pcl_iter;
  c.pcl.max_correspondence_distance = 0.25 * D;
  c.pcl.ndt_resolution = D / 20.0;
  c.pcl.ndt_step_size = c.pcl.ndt_resolution / 4.0;
  c.pcl.transformation_epsilon = std::pow(1e-6 * D, 2);
  c.pcl.gicp_translation_epsilon = 1e-6 * D;
  c.discrepancy.max_distance = 3.0 * s;
  c.discrepancy.outward = true;
  char buf[256];
  std::snprintf(buf, sizeof(buf),
                "object rule: diagonal D = %.4g, spacing s = %.3g; PCL max_corr = D/4 = %.4g, NDT "
                "voxel D/20 = %.3g, step voxel/4, ICP trans_eps (1e-6 D)^2, GICP eps 1e-6 D",
                D, s, c.pcl.max_correspondence_distance, c.pcl.ndt_resolution);
  c.pcl_choice = buf;
}

/// Airborne strips: reach 2 m (≈ 10 point spacings at 25 pts/m², strip offsets are cm), NDT 2 m
/// voxels with a 0.5 m step (PclMethodSettings defaults, made for airborne data in metres).
void
airborneSettings(Case& c, int pcl_iter)
{
  const double s = pointSpacing(c.target);
  c.pcl.max_iterations = pcl_iter;
  c.discrepancy.max_distance = 1.0;
  c.discrepancy.outward = false;
  char buf[256];
  std::snprintf(buf, sizeof(buf),
                "airborne rule: spacing s = %.3g m; PCL max_corr = 2 m, NDT voxel 2 m step 0.5 m, "
                "trans_eps 1e-10 m^2, GICP eps 1e-5 m",
                s);
  c.pcl_choice = buf;
}

/// Spinning-LiDAR scans (street, 1–80 m ranges): reach 2 m (above the 1.2 m odometry step), NDT
/// 1 m voxels with a 0.25 m step, the usual choices for Velodyne odometry with PCL.
void
scanSettings(Case& c, int pcl_iter)
{
  const double s = pointSpacing(c.target);
  c.pcl.max_iterations = pcl_iter;
  c.pcl.ndt_resolution = 1.0;
  c.pcl.ndt_step_size = 0.25;
  c.discrepancy.max_distance = 0.5;
  c.discrepancy.outward = false;
  char buf[256];
  std::snprintf(buf, sizeof(buf),
                "spinning-scan rule: spacing s = %.3g m; PCL max_corr = 2 m, NDT voxel 1 m step "
                "0.25 m, trans_eps 1e-10 m^2, GICP eps 1e-5 m",
                s);
  c.pcl_choice = buf;
}

bool
load(const std::string& path, pcl::PointCloud<PointLiDAR>& cloud, io::CloudInfo& info,
     const io::LoadOptions& options = {})
{
  std::string error;
  if (!io::loadCloud(path, cloud, info, error, options)) {
    pcl::console::print_error("cannot read %s: %s\n", path.c_str(), error.c_str());
    return false;
  }
  return true;
}

/// Source and target from two files in one frame (the source's origin).
bool
loadPair(const std::string& src, const std::string& tgt, Case& c)
{
  pcl::PointCloud<PointLiDAR> a, b;
  io::CloudInfo ia, ib;
  if (!load(src, a, ia))
    return false;
  io::LoadOptions o;
  o.use_origin = true;
  o.origin = ia.origin;
  if (!load(tgt, b, ib, o))
    return false;
  c.source = toXYZ(a);
  c.target = toXYZ(b);
  return true;
}

/// Rotation angle [deg] of R_est R_trueᵀ and |t_est − t_true| (scale divided out of R).
void
rotationTranslationError(const Eigen::Matrix4d& est, const Eigen::Matrix4d& truth, double& rot_deg,
                         double& trans)
{
  Eigen::Matrix3d Re = est.topLeftCorner<3, 3>(), Rt = truth.topLeftCorner<3, 3>();
  Re /= std::cbrt(Re.determinant());
  Rt /= std::cbrt(Rt.determinant());
  const double c = std::clamp(((Re * Rt.transpose()).trace() - 1.0) / 2.0, -1.0, 1.0);
  rot_deg = std::acos(c) * 180.0 / M_PI;
  trans = (est.topRightCorner<3, 1>() - truth.topRightCorner<3, 1>()).norm();
}

struct Row
{
  RegistrationRun run;
  double rot_deg = kNaN, trans = kNaN;
  DiscrepancyStats after;
};

std::string
num(double v, const char* fmt, int width)
{
  char buf[64];
  if (std::isfinite(v))
    std::snprintf(buf, sizeof(buf), fmt, v);
  else
    std::snprintf(buf, sizeof(buf), "%*s", width, "-");
  return buf;
}

/// Runs every method on one case, prints its table and checks the targets.
/// Returns 1 when every target passed, 0 when one failed, -1 without targets.
int
runCase(Case& c, std::vector<std::string>& summary)
{
  std::printf("\n=== %s: %zu source / %zu target points\n", c.name.c_str(), c.source->size(),
              c.target->size());
  std::printf("PCL settings (%s)\n  %s\n", c.pcl_choice.c_str(), c.pcl.describe().c_str());
  Ls3dMethodSettings ls;
  ls.max_correspondence_distance = 0.0;  // class default: automatic reach
  ls.max_iterations = 0;                 // class default
  std::printf("LS3D settings: %s\n", ls.describe().c_str());

  std::vector<Row> rows;
  for (auto rule : {ConjugateRuleType::LND, ConjugateRuleType::LZD, ConjugateRuleType::ICP}) {
    rows.emplace_back();
    rows.back().run = runLs3d(rule, c.source, c.target, ls);
  }
  for (auto m : allPclMethods()) {
    rows.emplace_back();
    rows.back().run = runPclMethod(m, c.source, c.target, c.pcl);
  }

  const Eigen::Matrix3Xd src = cloudToMatrix(*c.source);
  SurfaceDiscrepancy disc(c.target, c.discrepancy);
  const DiscrepancyStats before = disc.evaluate(src, Eigen::Matrix4d::Identity());
  RunEvaluation evaluation(c.source, c.target, 3.0 * c.discrepancy.max_distance);
  double gicp_time = kNaN;
  for (auto& r : rows) {
    evaluation.evaluate(r.run, c.has_truth ? &c.truth : nullptr);
    if (c.has_truth)
      rotationTranslationError(r.run.transformation, c.truth, r.rot_deg, r.trans);
    r.after = disc.evaluate(src, r.run.transformation);
    if (r.run.name == "PCL-GICP" && r.run.ran)
      gicp_time = r.run.time_s;
  }

  std::printf("%-9s %4s %-14s %5s", "method", "iter", "stop", "trust");
  if (c.has_truth)
    std::printf(" %9s %10s %10s %10s", "rot[deg]", "trans", "mean", "max");
  std::printf(" %10s %10s %8s %8s %7s\n", "sMAD", "median", "wall[s]", "cpu[s]", "/GICP");
  for (const auto& r : rows) {
    std::printf("%-9s %4d %-14.14s %5s", r.run.name.c_str(), r.run.iterations,
                r.run.ran ? r.run.stop.c_str() : "FAILED", r.run.pcl_converged ? "yes" : "no");
    if (c.has_truth) {
      const bool ok = r.run.ran && r.run.error.valid;
      std::printf(" %s %s %s %s", num(r.rot_deg, "%9.4f", 9).c_str(), num(r.trans, "%10.3e", 10).c_str(),
                  num(ok ? r.run.error.mean : kNaN, "%10.3e", 10).c_str(),
                  num(ok ? r.run.error.max : kNaN, "%10.3e", 10).c_str());
    }
    std::printf(" %s %s %8.3f %8.3f %s\n", num(r.after.sigma_mad, "%10.3e", 10).c_str(),
                num(r.after.median, "%10.3e", 10).c_str(), r.run.time_s, r.run.cpu_s,
                num(r.run.time_s / gicp_time, "%7.2f", 7).c_str());
    if (!r.run.ran || (!r.run.pcl_converged && r.run.name.rfind("LS3D", 0) == 0))
      std::printf("          (%s)\n", r.run.message.c_str());
  }
  std::printf("before (identity): sMAD %s, median %s over %zu points; discrepancies: signed "
              "distance to the target's flat local plane (k %d, variation <= %.2f) within %.3g\n",
              num(before.sigma_mad, "%.3e", 1).c_str(), num(before.median, "%.3e", 1).c_str(), before.points,
              c.discrepancy.k, c.discrepancy.max_variation, c.discrepancy.max_distance);

  const Row& lnd = rows.front();
  char line[512];
  if (!c.has_truth || !c.check_targets) {
    std::snprintf(line, sizeof(line), "%-28s sMAD before %.3e, LND after %.3e (%s), LND wall/GICP %.2f",
                  c.name.c_str(), before.sigma_mad, lnd.after.sigma_mad, lnd.run.stop.c_str(),
                  lnd.run.time_s / gicp_time);
    summary.push_back(line);
    return -1;
  }
  double best = std::numeric_limits<double>::infinity();
  std::string best_name = "none";
  for (const auto& r : rows)
    if (r.run.name.rfind("PCL-", 0) == 0 && r.run.ran && r.run.error.valid && r.run.error.mean < best) {
      best = r.run.error.mean;
      best_name = r.run.name;
    }
  const bool lnd_ok = lnd.run.ran && lnd.run.error.valid;
  const double acc = lnd_ok ? best / lnd.run.error.mean : kNaN;
  const double time = lnd.run.time_s / gicp_time;
  const bool pass_acc = std::isfinite(acc) && acc >= 1.0;
  const bool pass_time = std::isfinite(time) && time <= 1.0;
  std::printf("targets: best PCL mean error (%s %.3e) / LS3D-LND mean error (%.3e) = %.3f (>= 1) "
              "%s; LS3D-LND wall / PCL-GICP wall = %.3f (<= 1) %s; LS3D-LND trusted: %s\n",
              best_name.c_str(), best, lnd_ok ? lnd.run.error.mean : kNaN, acc, pass_acc ? "PASS" : "FAIL",
              time, pass_time ? "PASS" : "FAIL", lnd.run.pcl_converged ? "yes" : "NO");
  std::snprintf(line, sizeof(line), "%-28s accuracy x%.3f (LND %.3e vs %s %.3e) %s; time ratio %.3f %s",
                c.name.c_str(), acc, lnd_ok ? lnd.run.error.mean : kNaN, best_name.c_str(), best,
                pass_acc ? "PASS" : "FAIL", time, pass_time ? "PASS" : "FAIL");
  summary.push_back(line);
  return pass_acc && pass_time ? 1 : 0;
}

/// Two largest strips of an IGN tile as target (lower id) and source.
bool
ignCase(const std::string& path, Case& c)
{
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  if (!load(path, cloud, info))
    return false;
  auto strips = io::splitByPointSource(cloud);
  std::vector<std::pair<std::size_t, std::uint16_t>> bySize;
  for (const auto& s : strips)
    bySize.emplace_back(s.second.size(), s.first);
  std::sort(bySize.rbegin(), bySize.rend());
  if (bySize.size() < 2 || bySize[1].first < 1000) {
    pcl::console::print_warn("%s: fewer than two strips with 1000 points; skipped\n", path.c_str());
    return false;
  }
  const std::uint16_t a = std::min(bySize[0].second, bySize[1].second);
  const std::uint16_t b = std::max(bySize[0].second, bySize[1].second);
  pcl::PointCloud<PointLiDAR> target, source;
  pcl::copyPointCloud(cloud, strips[a], target);
  pcl::copyPointCloud(cloud, strips[b], source);
  c.target = toXYZ(target);
  c.source = toXYZ(source);
  const auto slash = path.find_last_of('/');
  c.name = "IGN " + path.substr(slash + 1, path.size() - slash - 5) + " strip " + std::to_string(b) + "->" +
           std::to_string(a);
  return true;
}

}  // namespace

int
main(int argc, char** argv)
{
  if (pcl::console::find_switch(argc, argv, "-h")) {
    printHelp(argv[0]);
    return 0;
  }
  std::string data = PCL_LS3D_SHARED_DATA_DIR, pairs = "bun,dragon,bunny,ign,spin";
  int pcl_iter = 200;
  pcl::console::parse_argument(argc, argv, "-data", data);
  pcl::console::parse_argument(argc, argv, "-pairs", pairs);
  pcl::console::parse_argument(argc, argv, "-pcl_iter", pcl_iter);
  if (pcl_iter < 1) {
    pcl::console::print_error("-pcl_iter must be >= 1\n");
    return 1;
  }
  const std::string reg = data + "/registration";
  auto wanted = [&](const char* what) {
    return (',' + pairs + ',').find(',' + std::string(what) + ',') != std::string::npos;
  };
  const bool generated_only = pairs == "spin";
  if (!generated_only && !fileExists(reg + "/pcl/bun0.pcd")) {
    pcl::console::print_error("shared data not found: %s/pcl/bun0.pcd is missing. Point -data at "
                              "the shared data folder (see its MANIFEST.md).\n",
                              reg.c_str());
    return 1;
  }

  std::vector<std::string> summary;
  int failed = 0, checked = 0;
  auto account = [&](int r) {
    if (r >= 0) {
      ++checked;
      failed += r == 0;
    }
  };

  if (wanted("bun")) {
    Case c;
    c.name = "PCL bun0->bun4";
    if (loadPair(reg + "/pcl/bun0.pcd", reg + "/pcl/bun4.pcd", c)) {
      c.has_truth = c.check_targets = true;
      // PCL master test/registration/test_registration.cpp, TEST(PCL, PPFRegistration).
      c.truth << 0.825336, 0, -0.564642, 0.037267, 0, 1, 0, 0, 0.564642, 0, 0.825336, 0.038325, 0, 0, 0, 1;
      objectSettings(c, pcl_iter);
      account(runCase(c, summary));
    }
  }
  if (wanted("dragon")) {
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    T.topLeftCorner<3, 3>() = (Eigen::AngleAxisd(M_PI / 180.0, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(3.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
    T.topRightCorner<3, 1>() << 0.2, 0.4, 0.6;
    for (int k : {2, 3}) {
      Case c;
      c.name = "simpleICP dragon1->dragon" + std::to_string(k);
      if (!loadPair(reg + "/simpleicp/dragon1.xyz", reg + "/simpleicp/dragon" + std::to_string(k) + ".xyz",
                    c))
        continue;
      c.has_truth = c.check_targets = true;
      c.truth = T;
      if (k == 3)
        c.truth(2, 3) += 1.0;  // dragon3 = dragon2 + (0, 0, 1)
      objectSettings(c, pcl_iter);
      account(runCase(c, summary));
    }
  }
  if (wanted("bunny")) {
    Case c;
    c.name = "simpleICP bunny part2->part1";
    if (loadPair(reg + "/simpleicp/bunny_part2.xyz", reg + "/simpleicp/bunny_part1.xyz", c)) {
      objectSettings(c, pcl_iter);
      account(runCase(c, summary));
    }
  }
  if (wanted("ign")) {
    for (const char* tile : {"test_data_77050_627755_LA93_IGN69", "test_data_77055_627755_LA93_IGN69",
                             "test_data_77050_627760_LA93_IGN69", "test_data_77055_627760_LA93_IGN69",
                             "test_data_77060_627760_LA93_IGN69", "las_with_origin_dsmMarker",
                             "sample_lareunion_epsg2975", "target_cloud_crop"}) {
      Case c;
      if (!ignCase(reg + "/ign_lidarhd/" + tile + ".las", c))
        continue;
      airborneSettings(c, pcl_iter);
      account(runCase(c, summary));
    }
  }

  if (wanted("spin")) {
    // Generated: the project has no Velodyne recording. HDL-32E-like street scans with truth,
    // a 10 Hz scan step at 22 and at 43 km/h, registered from the identity.
    for (double step : {0.6, 1.2}) {
      const synth::SpinningScanPair pair = synth::makeSpinningScanPair(step);
      Case c;
      char name[96];
      std::snprintf(name, sizeof(name), "generated HDL-32E street scans %.1f m apart", step);
      c.name = name;
      c.source = pair.source;
      c.target = pair.target;
      c.has_truth = c.check_targets = true;
      c.truth = pair.truth;
      scanSettings(c, pcl_iter);
      account(runCase(c, summary));
    }
  }

  std::printf("\nsummary (targets on pairs with a reference: LS3D-LND mean error <= best PCL, "
              "wall time <= PCL-GICP):\n");
  for (const auto& s : summary)
    std::printf("  %s\n", s.c_str());
  std::printf("pairs with targets: %d, failed: %d -> %s\n", checked, failed, failed == 0 ? "PASS" : "FAIL");
  return failed == 0 ? 0 : 2;
}
