// benchmark_registration: LS3D (LND, LZD, ICP rules) against pcl::IterativeClosestPoint,
// IterativeClosestPointWithNormals, GeneralizedIterativeClosestPoint and
// NormalDistributionsTransform on one generated pair, in one process, and the targets:
//   (1) LS3D-LND mean displacement error <= 1/5 of the best PCL method's,
//   (2) LS3D-LND wall time <= 0.5 x PCL point-to-plane ICP's (normal estimation included),
//   (3) LS3D-LND >= 20x more accurate (mean displacement) than PCL point-to-point ICP.
#include <pcl_ls3d/evaluation/comparison_report.h>
#include <pcl_ls3d/evaluation/ls3d_method.h>
#include <pcl_ls3d/evaluation/pcl_methods.h>
#include <pcl_ls3d/synth/registration_pair.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>

using namespace pcl_ls3d;
using namespace pcl_ls3d::evaluation;

namespace {

void
printHelp(const char* name)
{
  pcl::console::print_info(
      "Usage: %s [options]\n"
      "  -seed S          generator seed (default 1)\n"
      "  -size L          square footprint edge [m] (default 300: ~90k source / 360k target)\n"
      "  -json FILE       also write the comparison as JSON (refuses to overwrite)\n"
      "  -h               this help\n",
      name);
}

/// Prints one target line and returns whether it passed.
bool
checkTarget(const char* what, double ratio, double bound, bool at_most)
{
  const bool pass = std::isfinite(ratio) && (at_most ? ratio <= bound : ratio >= bound);
  std::printf("  %-62s %10.3f (%s %.2f)  %s\n", what, ratio, at_most ? "<=" : ">=", bound,
              pass ? "PASS" : "FAIL");
  return pass;
}

const RegistrationRun*
find(const std::vector<RegistrationRun>& runs, const std::string& name)
{
  for (const auto& r : runs)
    if (r.name == name)
      return &r;
  return nullptr;
}

}  // namespace

int
main(int argc, char** argv)
{
  if (pcl::console::find_switch(argc, argv, "-h")) {
    printHelp(argv[0]);
    return 0;
  }
  synth::RegistrationPairSettings ps;
  int seed = 1;
  double size = 300.0;
  std::string json_path;
  pcl::console::parse_argument(argc, argv, "-seed", seed);
  pcl::console::parse_argument(argc, argv, "-size", size);
  pcl::console::parse_argument(argc, argv, "-json", json_path);
  if (seed < 0 || !(size > 10.0)) {
    pcl::console::print_error("-seed must be >= 0 and -size > 10 m\n");
    return 1;
  }
  if (!json_path.empty() && std::ifstream(json_path).good()) {
    pcl::console::print_error("%s exists; refusing to overwrite\n", json_path.c_str());
    return 1;
  }
  ps.seed = static_cast<std::uint32_t>(seed);
  ps.size_x = ps.size_y = size;  // defaults: 1 vs 4 pts/m², 70 % overlap, σ = 5 cm

  pcl::console::TicToc tt;
  tt.tic();
  const synth::RegistrationPair pair = synth::makeRegistrationPair(ps);
  const auto source = toXYZ(*pair.source);
  const auto target = toXYZ(*pair.target);
  std::printf("pair: %zu source / %zu target points, %.0f x %.0f m, densities %.1f / %.1f pts/m2, "
              "overlap %.0f %%, noise %.3f m, seed %d (generated in %.1f s)\n",
              source->size(), target->size(), ps.size_x, ps.size_y, ps.source_density,
              ps.target_density, ps.overlap * 100.0, ps.noise_sigma, seed, tt.toc() / 1000.0);

  const PclMethodSettings pcl_settings;
  const Ls3dMethodSettings ls3d_settings;
  std::printf("PCL settings : %s\nLS3D settings: %s\n", pcl_settings.describe().c_str(),
              ls3d_settings.describe().c_str());

  const Eigen::Matrix4d truth = pair.truth.matrix();
  const double rms_cut = 1.0;
  RunEvaluation evaluation(source, target, rms_cut);
  std::vector<RegistrationRun> runs;
  for (auto rule : {ConjugateRuleType::LND, ConjugateRuleType::LZD, ConjugateRuleType::ICP})
    runs.push_back(runLs3d(rule, source, target, ls3d_settings));
  for (auto m : allPclMethods())
    runs.push_back(runPclMethod(m, source, target, pcl_settings));
  for (auto& r : runs) {
    evaluation.evaluate(r, &truth);
    if (r.normals_time_s > 0)
      std::printf("%s: normal estimation %.3f s of %.3f s\n", r.name.c_str(), r.normals_time_s,
                  r.time_s);
  }
  std::printf("\n%s", formatComparisonTable(runs, true).c_str());
  std::printf("(RMS: nearest-neighbour distances within %.1f m; errors against the known truth)\n\n",
              rms_cut);

  const RegistrationRun* lnd = find(runs, "LS3D-LND");
  const RegistrationRun* icp = find(runs, "PCL-ICP");
  const RegistrationRun* icpn = find(runs, "PCL-ICP-N");
  double best_pcl = std::numeric_limits<double>::infinity();
  std::string best_name = "none";
  for (const auto& r : runs)
    if (r.name.rfind("PCL-", 0) == 0 && r.ran && r.error.valid && r.error.mean < best_pcl) {
      best_pcl = r.error.mean;
      best_name = r.name;
    }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool lnd_ok = lnd && lnd->ran && lnd->error.valid;
  std::printf("targets (LS3D-LND):\n");
  char what[128];
  std::snprintf(what, sizeof(what), "best PCL mean error (%s) / LS3D-LND mean error",
                best_name.c_str());
  bool all = checkTarget(what, lnd_ok ? best_pcl / lnd->error.mean : nan, 5.0, false);
  all &= checkTarget("LS3D-LND time / PCL-ICP-N time (normals included)",
                lnd_ok && icpn ? lnd->time_s / icpn->time_s : nan, 0.5, true);
  all &= checkTarget("PCL-ICP mean error / LS3D-LND mean error",
                lnd_ok && icp && icp->error.valid ? icp->error.mean / lnd->error.mean : nan, 20.0,
                false);
  if (lnd_ok && icpn && icpn->cpu_s > 0)
    std::printf("  (info) LS3D-LND CPU time / PCL-ICP-N CPU time: %.3f; LS3D-LND wall / CPU: %.2f / "
                "%.2f s\n",
                lnd->cpu_s / icpn->cpu_s, lnd->time_s, lnd->cpu_s);
  std::printf("overall: %s\n", all ? "PASS" : "FAIL");

  if (!json_path.empty()) {
    ComparisonContext c;
    c.source = "synth pair source (seed " + std::to_string(seed) + ")";
    c.target = "synth pair target";
    c.origin = pair.origin;
    c.source_points = source->size();
    c.target_points = target->size();
    c.has_truth = true;
    c.rms_max_distance = rms_cut;
    c.pcl_settings = pcl_settings.describe();
    c.ls3d_settings = ls3d_settings.describe();
    std::ofstream(json_path) << comparisonJson(runs, c) << "\n";
  }
  return all ? 0 : 2;
}
