// benchmark_registration: LS3D against PCL's ICP family on generated pairs, in one process,
// like with like (issue 10, "Fair comparison"):
//  1. RIGID pair (truth m = 1): LS3D (LND, LZD, ICP rules; rigid, the class default) against
//     pcl::IterativeClosestPoint, IterativeClosestPointWithNormals,
//     GeneralizedIterativeClosestPoint and NormalDistributionsTransform, PCL's iteration limit
//     high enough (default 200) that they converge — each row says whether it hit the limit.
//     Targets: (1) LS3D-LND mean displacement error >= 3x smaller than the best PCL method's;
//              (2) LS3D-LND wall time <= PCL-GICP's.
//  2. SIMILARITY pair (truth m = 1 + 2e-4): LS3D-LND with 7 parameters against
//     pcl::IterativeClosestPoint with TransformationEstimationSVDScale (PCL-ICP-S) and the rigid
//     PCL-ICP (information, no target).
// Wall and CPU times are reported; run `uptime` beside it, ratios are the figures that matter.
#include <pcl_ls3d/evaluation/comparison_report.h>
#include <pcl_ls3d/evaluation/ls3d_method.h>
#include <pcl_ls3d/evaluation/pcl_methods.h>
#include <pcl_ls3d/synth/registration_pair.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cmath>
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
      "  -size L          square footprint edge of the rigid pair [m] (default 300: ~90k source /\n"
      "                   360k target points)\n"
      "  -sim_size L      footprint edge of the similarity pair [m] (default 300; 0 = skip it)\n"
      "  -pcl_iter N      iteration limit of the PCL methods (default 200)\n"
      "  -json FILE       also write the rigid comparison as JSON (refuses to overwrite)\n"
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

struct Pair
{
  synth::RegistrationPair pair;
  pcl::PointCloud<pcl::PointXYZ>::Ptr source, target;
};

Pair
makePair(const synth::RegistrationPairSettings& ps, const char* label)
{
  pcl::console::TicToc tt;
  tt.tic();
  Pair p;
  p.pair = synth::makeRegistrationPair(ps);
  p.source = toXYZ(*p.pair.source);
  p.target = toXYZ(*p.pair.target);
  std::printf("%s pair: %zu source / %zu target points, %.0f x %.0f m, densities %.1f / %.1f "
              "pts/m2, overlap %.0f %%, noise %.3f m, seed %u, truth m - 1 = %.1f ppm (generated "
              "in %.1f s)\n",
              label, p.source->size(), p.target->size(), ps.size_x, ps.size_y, ps.source_density,
              ps.target_density, ps.overlap * 100.0, ps.noise_sigma, ps.seed, (ps.truth.m - 1.0) * 1e6,
              tt.toc() / 1000.0);
  return p;
}

void
printRuns(std::vector<RegistrationRun>& runs, const Pair& p, double rms_cut)
{
  const Eigen::Matrix4d truth = p.pair.truth.matrix();
  RunEvaluation evaluation(p.source, p.target, rms_cut);
  for (auto& r : runs) {
    evaluation.evaluate(r, &truth);
    if (r.normals_time_s > 0)
      std::printf("%s: normal estimation %.3f s of %.3f s\n", r.name.c_str(), r.normals_time_s, r.time_s);
  }
  std::printf("\n%s", formatComparisonTable(runs, true).c_str());
  std::printf("(conv: stopped by its own criterion; stop LIMIT / MAX_ITERATIONS: hit the "
              "iteration limit; trust: hasConverged(); RMS: nearest-neighbour distances within "
              "%.1f m; errors against the known truth)\n",
              rms_cut);
  for (const auto& r : runs)
    if (r.hit_limit)
      std::printf("  note: %s hit its iteration limit (%d) and did not converge\n", r.name.c_str(),
                  r.iterations);
  std::printf("\n");
}

}  // namespace

int
main(int argc, char** argv)
{
  if (pcl::console::find_switch(argc, argv, "-h")) {
    printHelp(argv[0]);
    return 0;
  }
  int seed = 1, pcl_iter = 200;
  double size = 300.0, sim_size = 300.0;
  std::string json_path;
  pcl::console::parse_argument(argc, argv, "-seed", seed);
  pcl::console::parse_argument(argc, argv, "-size", size);
  pcl::console::parse_argument(argc, argv, "-sim_size", sim_size);
  pcl::console::parse_argument(argc, argv, "-pcl_iter", pcl_iter);
  pcl::console::parse_argument(argc, argv, "-json", json_path);
  if (seed < 0 || !(size > 10.0) || !(sim_size == 0.0 || sim_size > 10.0) || pcl_iter < 1) {
    pcl::console::print_error("-seed must be >= 0, -size > 10 m, -sim_size 0 or > 10 m, "
                              "-pcl_iter >= 1\n");
    return 1;
  }
  if (!json_path.empty() && std::ifstream(json_path).good()) {
    pcl::console::print_error("%s exists; refusing to overwrite\n", json_path.c_str());
    return 1;
  }

  // ---- 1. rigid pair: LS3D rigid (class default) vs PCL's ICP family ----------------------
  synth::RegistrationPairSettings ps;  // 1 vs 4 pts/m², 70 % overlap, σ = 5 cm
  ps.seed = static_cast<std::uint32_t>(seed);
  ps.size_x = ps.size_y = size;
  ps.truth = synth::defaultPairTruth();
  ps.truth.m = 1.0;  // rigid truth: the scale is not part of this comparison
  const Pair rigid = makePair(ps, "rigid");

  PclMethodSettings pcl_settings;
  pcl_settings.max_iterations = pcl_iter;
  Ls3dMethodSettings ls3d_settings;  // rigid (6 parameters), 2 m like PCL, 30 iterations
  std::printf("PCL settings : %s\nLS3D settings: %s\n", pcl_settings.describe().c_str(),
              ls3d_settings.describe().c_str());

  std::vector<RegistrationRun> runs;
  for (auto rule : {ConjugateRuleType::LND, ConjugateRuleType::LZD, ConjugateRuleType::ICP})
    runs.push_back(runLs3d(rule, rigid.source, rigid.target, ls3d_settings));
  for (auto m : allPclMethods())
    runs.push_back(runPclMethod(m, rigid.source, rigid.target, pcl_settings));
  const double rms_cut = 1.0;
  printRuns(runs, rigid, rms_cut);

  const RegistrationRun* lnd = find(runs, "LS3D-LND");
  const RegistrationRun* gicp = find(runs, "PCL-GICP");
  double best_pcl = std::numeric_limits<double>::infinity();
  std::string best_name = "none";
  for (const auto& r : runs)
    if (r.name.rfind("PCL-", 0) == 0 && r.ran && r.error.valid && r.error.mean < best_pcl) {
      best_pcl = r.error.mean;
      best_name = r.name;
    }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool lnd_ok = lnd && lnd->ran && lnd->error.valid;
  std::printf("targets (rigid pair, LS3D-LND rigid):\n");
  char what[128];
  std::snprintf(what, sizeof(what), "best PCL mean error (%s) / LS3D-LND mean error", best_name.c_str());
  bool all = checkTarget(what, lnd_ok ? best_pcl / lnd->error.mean : nan, 3.0, false);
  all &= checkTarget("LS3D-LND wall time / PCL-GICP wall time",
                     lnd_ok && gicp && gicp->ran ? lnd->time_s / gicp->time_s : nan, 1.0, true);
  if (lnd_ok && gicp && gicp->cpu_s > 0)
    std::printf("  (info) LS3D-LND CPU time / PCL-GICP CPU time: %.3f; LS3D-LND wall / CPU: %.2f / "
                "%.2f s; LS3D-LND trusted: %s\n",
                lnd->cpu_s / gicp->cpu_s, lnd->time_s, lnd->cpu_s, lnd->pcl_converged ? "yes" : "NO");

  if (!json_path.empty()) {
    ComparisonContext c;
    c.source = "synth rigid pair source (seed " + std::to_string(seed) + ")";
    c.target = "synth rigid pair target";
    c.origin = rigid.pair.origin;
    c.source_points = rigid.source->size();
    c.target_points = rigid.target->size();
    c.has_truth = true;
    c.rms_max_distance = rms_cut;
    c.pcl_settings = pcl_settings.describe();
    c.ls3d_settings = ls3d_settings.describe();
    std::ofstream(json_path) << comparisonJson(runs, c) << "\n";
  }

  // ---- 2. similarity pair: LS3D 7 parameters vs PCL ICP with SVD scale estimation ---------
  if (sim_size > 0.0) {
    synth::RegistrationPairSettings ss = ps;
    ss.size_x = ss.size_y = sim_size;
    ss.truth = synth::defaultPairTruth();  // m = 1 + 2e-4
    std::printf("\n");
    const Pair sim = makePair(ss, "similarity");
    Ls3dMethodSettings ls7 = ls3d_settings;
    ls7.model = ParameterModel::SIMILARITY_7;
    std::printf("LS3D settings: %s\n", ls7.describe().c_str());
    std::vector<RegistrationRun> sruns;
    sruns.push_back(runLs3d(ConjugateRuleType::LND, sim.source, sim.target, ls7));
    sruns.back().name = "LS3D-LND-7";
    sruns.push_back(runLs3d(ConjugateRuleType::LND, sim.source, sim.target, ls3d_settings));
    sruns.back().name = "LS3D-LND-6";
    sruns.push_back(runPclMethod(PclMethod::ICP_SCALE, sim.source, sim.target, pcl_settings));
    sruns.push_back(runPclMethod(PclMethod::ICP, sim.source, sim.target, pcl_settings));
    printRuns(sruns, sim, rms_cut);
    const RegistrationRun* l7 = find(sruns, "LS3D-LND-7");
    const RegistrationRun* is = find(sruns, "PCL-ICP-S");
    if (l7 && is && l7->error.valid && is->error.valid)
      std::printf("similarity pair (information): PCL-ICP-S / LS3D-LND-7 mean error %.2f; "
                  "scale error %.1f vs %.1f ppm; wall time ratio LS3D-LND-7 / PCL-ICP-S %.3f\n",
                  is->error.mean / l7->error.mean, is->error.parameters[6] * 1e6,
                  l7->error.parameters[6] * 1e6, l7->time_s / is->time_s);
  }
  std::printf("overall (rigid targets): %s\n", all ? "PASS" : "FAIL");
  return all ? 0 : 2;
}
