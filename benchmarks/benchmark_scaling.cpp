// benchmark_scaling: LS3D-LND on two generated flight strips with 20 % side overlap, at several
// strip sizes (default 0.5, 1, 2, 5 M points per strip). Each size runs in a FRESH child process
// (this executable re-executed with -child N), so every peak-memory figure belongs to one size:
//   - process peak: the child's ru_maxrss from wait4() (generation + registration),
//   - align peak:   VmHWM after align() with the high-water mark reset (clear_refs = 5) just
//                   before it, i.e. input clouds held + everything LS3D allocates.
// Target (issue): 5 M-point strips registered in <= 30 s on 2 cores with <= 4 GB peak.
#include "process_memory.h"

#include <pcl_ls3d/evaluation/ls3d_method.h>
#include <pcl_ls3d/evaluation/transform_error.h>
#include <pcl_ls3d/registration/least_squares_surface_matching.h>
#include <pcl_ls3d/rules/lnd_rule.h>
#include <pcl_ls3d/synth/strip_block.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl_ls3d;

namespace {

/// Child: generate, register strip 2 onto strip 1, print one RESULT line.
/// LS3D-LND with Zuo's TIN facet as the local surface (LndRule::Surface::TRIANGLE), same
/// settings as runLs3d(): the accurate reference while the quadric LND fails on zig-zag strips.
evaluation::RegistrationRun
runTriangleLnd(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& source,
               const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& target,
               const evaluation::Ls3dMethodSettings& settings)
{
  evaluation::RegistrationRun run;
  pcl::console::TicToc tt;
  tt.tic();
  const double cpu0 = evaluation::processCpuSeconds();
  LeastSquaresSurfaceMatching<pcl::PointXYZ, pcl::PointXYZ> ls3d;
  ls3d.setConjugateRule(std::make_shared<LndRule>(12, LndRule::Surface::TRIANGLE));
  ls3d.setMaxCorrespondenceDistance(settings.max_correspondence_distance);
  ls3d.setMaximumIterations(settings.max_iterations);
  ls3d.setSourceThinning(settings.source_thinning);
  ls3d.setInputSource(source);
  ls3d.setInputTarget(target);
  pcl::PointCloud<pcl::PointXYZ> output;
  ls3d.align(output);
  run.time_s = tt.toc() / 1000.0;
  run.cpu_s = evaluation::processCpuSeconds() - cpu0;
  const AdjustmentReport& report = ls3d.getReport();
  run.ran = true;
  run.iterations = report.iterations;
  run.converged = report.termination == TerminationType::CONVERGED;
  run.sigma0 = report.sigma0;
  run.transformation = report.transformation;
  run.message = terminationTypeToString(report.termination);
  return run;
}

int
runChild(long points_per_strip, unsigned int seed, bool parallel, double thin, bool triangle)
{
  synth::StripSettings s;
  s.pattern = parallel ? synth::ScanPattern::PARALLEL : synth::ScanPattern::ZIGZAG;
  s.seed = seed;
  s.num_strips = 2;
  s.side_overlap = 0.2;
  s.swath_width = 300.0;
  s.density = 4.0;  // 600 points per scan line, 1200 points per metre of strip
  s.strip_length = static_cast<double>(points_per_strip) / (s.density * s.swath_width);
  pcl::console::TicToc tt;
  tt.tic();
  pcl::PointCloud<pcl::PointXYZ>::Ptr target, source;
  Eigen::Matrix4d truth;
  {
    const synth::StripBlock block = synth::makeStripBlock(s);
    if (block.strips.size() != 2)
      return 1;
    target = evaluation::toXYZ(*block.stripCloud(0));
    source = evaluation::toXYZ(*block.stripCloud(1));
    // observed strip 2 -> true frame -> observed strip 1 (identity when strip 1 is fixed)
    truth = block.strips[0].transform.inverse().matrix() * block.strips[1].transform.matrix();
  }  // the block and its copies are freed here
  const double gen_s = tt.toc() / 1000.0;

  const bool reset = bench_process::resetPeak();
  const long rss_before = bench_process::statusKb("VmRSS");
  evaluation::Ls3dMethodSettings ls;
  ls.source_thinning = thin;
  const auto run = triangle ? runTriangleLnd(source, target, ls)
                            : evaluation::runLs3d(ConjugateRuleType::LND, source, target, ls);
  const long hwm = bench_process::statusKb("VmHWM");
  const auto err =
      evaluation::computeTransformError(run.transformation, truth, evaluation::cloudToMatrix(*source));
  std::printf("RESULT %zu %zu %.3f %.3f %.3f %d %d %.6f %.6f %.5f %ld %ld %d %s\n", source->size(),
              target->size(), gen_s, run.time_s, run.cpu_s, run.iterations, run.converged ? 1 : 0, err.mean,
              err.max, run.sigma0, rss_before, hwm, reset ? 1 : 0, run.message.substr(0, 60).c_str());
  return run.ran ? 0 : 1;
}

/// Accuracy sanity bound on the mean displacement error [m] (not an issue target).
constexpr double kMaxMeanError = 0.05;

/// Re-executes this program with -child N and collects its RESULT line and rusage.
bench_process::ChildResult
spawnChild(long n, unsigned int seed, bool parallel, double thin, bool triangle)
{
  return bench_process::runChild({"benchmark_scaling", "-child", std::to_string(n), "-seed",
                                  std::to_string(seed), parallel ? "-parallel" : "-zigzag", "-thin",
                                  std::to_string(thin), triangle ? "-triangle" : "-quadric"});
}

}  // namespace

int
main(int argc, char** argv)
{
  if (pcl::console::find_switch(argc, argv, "-h")) {
    pcl::console::print_info(
        "Usage: %s [-sizes 0.5,1,2,5] [-seed S] [-parallel] [-thin STEP] [-triangle]\n"
        "  -sizes     points per strip in millions (default 0.5,1,2,5)\n"
        "  -parallel  rotating-polygon scan lines instead of zig-zag\n"
        "  -thin      one source observation per voxel of this edge [m] (default 0: all)\n"
        "  -triangle  LND on Zuo's TIN facet instead of the local quadric\n",
        argv[0]);
    return 0;
  }
  int seed = 1;
  pcl::console::parse_argument(argc, argv, "-seed", seed);
  const bool parallel = pcl::console::find_switch(argc, argv, "-parallel");
  const bool triangle = pcl::console::find_switch(argc, argv, "-triangle");
  double thin = 0.0;
  pcl::console::parse_argument(argc, argv, "-thin", thin);
  if (!(thin >= 0.0)) {
    pcl::console::print_error("-thin must be >= 0\n");
    return 1;
  }
  long child = 0;
  if (pcl::console::parse_argument(argc, argv, "-child", child) >= 0)
    return runChild(child, static_cast<unsigned int>(seed), parallel, thin, triangle);

  std::vector<double> sizes{0.5, 1.0, 2.0, 5.0};
  pcl::console::parse_x_arguments(argc, argv, "-sizes", sizes);
  std::printf("LS3D-LND (%s), 2 strips, 300 m swath, 20 %% side overlap, 4 pts/m2, %s scan, sigma 5 cm, "
              "seed %d, source thinning %g m; %ld threads; one fresh process per size\n\n",
              triangle ? "TIN facet" : "local quadric", parallel ? "parallel" : "zig-zag", seed, thin,
              sysconf(_SC_NPROCESSORS_ONLN));
  std::printf("%10s %10s %7s %8s %8s %5s %5s %9s %9s %8s %10s %10s  %s\n", "src_pts", "tgt_pts", "gen[s]",
              "reg[s]", "cpu[s]", "iter", "conv", "mean[mm]", "max[mm]", "s0[m]", "align_MB", "proc_MB",
              "status");
  bool pass = true, ran_target_size = false, accurate = true;
  for (double m : sizes) {
    const long n = static_cast<long>(m * 1e6);
    const bench_process::ChildResult r =
        spawnChild(n, static_cast<unsigned int>(seed), parallel, thin, triangle);
    if (r.line.empty()) {
      std::printf("%10ld  child failed\n", n);
      pass = false;
      continue;
    }
    std::istringstream in(r.line);
    std::size_t ns, nt;
    double gen, reg, cpu, mean, max, s0;
    int iter, conv, reset;
    long rss_before, hwm;
    std::string status;
    in >> ns >> nt >> gen >> reg >> cpu >> iter >> conv >> mean >> max >> s0 >> rss_before >> hwm >> reset;
    std::getline(in, status);
    std::printf("%10zu %10zu %7.1f %8.2f %8.2f %5d %5s %9.2f %9.2f %8.4f %10.0f %10.0f %s%s\n", ns, nt, gen,
                reg, cpu, iter, conv ? "yes" : "no", mean * 1e3, max * 1e3, s0, hwm / 1024.0,
                r.maxrss_kb / 1024.0, reset ? "" : "(HWM not reset) ", status.c_str());
    std::fflush(stdout);
    ran_target_size |= m >= 5.0;
    if (m >= 5.0 && (reg > 30.0 || r.maxrss_kb > 4L * 1024 * 1024 || !r.ok))
      pass = false;
    // A fast wrong answer is no success: 5 cm is ~10x the errors a working LND reaches here.
    accurate &= conv == 1 && mean <= kMaxMeanError;
  }
  std::printf("\nreg: wall time of setInput* + align(); cpu: its process CPU time (all threads).\n"
              "align_MB: peak RSS from just before align() (input clouds held) to its end; "
              "proc_MB: whole child process peak (generation included).\n");
  pass &= ran_target_size;
  std::printf("target 5 M points/strip: reg <= 30 s and peak <= 4096 MB: %s\n",
              !ran_target_size ? "NOT RUN (no size >= 5 M)" : (pass ? "PASS" : "FAIL"));
  std::printf("sanity: every size converged with mean displacement error <= %.0f mm: %s\n",
              kMaxMeanError * 1e3, accurate ? "PASS" : "FAIL");
  return pass && accurate ? 0 : 2;
}
