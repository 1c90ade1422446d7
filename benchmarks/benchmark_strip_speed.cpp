// benchmark_strip_speed: time and memory of the strip block adjustment (LND, rigid, defaults) on
// generated blocks (rolling terrain with buildings, 5 cm noise, random errors). Each size runs in
// a FRESH child process (this executable with -child), so every memory figure belongs to one
// size: "adjust peak" = VmHWM during run() with the high-water mark reset just before it (the
// strips held + everything the adjustment allocates; the generator's cloud is freed first),
// "process peak" = the child's ru_maxrss (generation included).
//   -pair: 2 strips of P M points (default 5), 20 % side overlap, 4 pts/m², swath 500 m.
//          Target (issue 8): ≤ 15 s on 2 cores, ≤ 4 GB.
//   -block 5,10,20,40: N parallel strips of P M points (default 1), 20 % side overlap, 2 pts/m²,
//          swath 200 m, plus 2 cross strips; growth per strip and per overlap printed.
//          Target: 20 strips ≤ 90 s, ≤ 6 GB; growth linear in points and overlaps.
#include "process_memory.h"
#include "strip_bench_common.h"

#include <pcl/console/parse.h>

#include <cstdio>
#include <sstream>

using namespace pcl_ls3d;
using namespace strip_bench;
using namespace bench_process;

namespace {

synth::StripSettings
speedBlock(int strips, int cross, double million_points, double swath, double density, double overlap)
{
  synth::StripSettings s;
  s.num_strips = strips;
  s.cross_strips = cross;
  s.swath_width = swath;
  s.density = density;
  s.side_overlap = overlap;
  s.strip_length = million_points * 1e6 / (swath * density);
  return s;
}

/// "plan/select/iterate/evaluate" seconds.
std::string
stageTimes(const strips::StripAdjustmentReport& r)
{
  std::ostringstream o;
  o.precision(1);
  o << std::fixed;
  for (std::size_t k = 0; k < r.timings_s.size(); ++k)
    o << (k ? "/" : "") << r.timings_s[k];
  return o.str();
}

/// Child: generate, free the cloud, adjust, print one RESULT line.
int
child(int strips, int cross, double mpts, double swath, double density, double overlap)
{
  const auto t0 = std::chrono::steady_clock::now();
  const Block b = makeBlock(speedBlock(strips, cross, mpts, swath, density, overlap));
  const double gen_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::size_t points = 0;
  for (const auto& s : b.strips)
    points += s.size();
  const bool reset = resetPeak();
  const Run r = adjust(b.strips, strips::StripAdjustmentSettings());
  const long hwm = statusKb("VmHWM");
  std::size_t used = 0;
  for (const auto& o : r.report.overlaps)
    used += o.used ? 1 : 0;
  std::printf("RESULT points %zu overlaps %zu generate_s %.1f adjust_s %.1f iterations %d termination %s "
              "adjust_peak_mb %.0f reset %d sigma0 %.4f stages %s\n",
              points, used, gen_s, r.seconds, r.report.iterations,
              terminationTypeToString(r.report.termination), static_cast<double>(hwm) / 1024.0, reset ? 1 : 0,
              r.report.sigma0, stageTimes(r.report).c_str());
  return r.ok ? 0 : 2;
}

double
field(const std::string& line, const std::string& key)
{
  std::istringstream in(line);
  std::string k;
  while (in >> k) {
    std::string v;
    in >> v;
    if (k == key)
      return std::atof(v.c_str());
  }
  return NAN;
}

std::vector<int>
parseList(const std::string& text)
{
  std::vector<int> out;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    out.push_back(std::atoi(item.c_str()));
  return out;
}

}  // namespace

int
main(int argc, char** argv)
{
  int strips = 0, cross = 2;
  double mpts = 0.0, swath = 200.0, density = 2.0, overlap = 0.2;
  std::string block_sizes;
  if (pcl::console::parse_argument(argc, argv, "-child", strips) >= 0) {
    pcl::console::parse_argument(argc, argv, "-cross", cross);
    pcl::console::parse_argument(argc, argv, "-mpts", mpts);
    pcl::console::parse_argument(argc, argv, "-swath", swath);
    pcl::console::parse_argument(argc, argv, "-density", density);
    return child(strips, cross, mpts, swath, density, overlap);
  }
  const bool pair = pcl::console::find_switch(argc, argv, "-pair");
  pcl::console::parse_argument(argc, argv, "-block", block_sizes);
  pcl::console::parse_argument(argc, argv, "-mpts", mpts);
  std::printf("benchmark_strip_speed: load %.2f\n", loadAverage());
  if (pair) {
    const double m = mpts > 0.0 ? mpts : 5.0;
    const ChildResult r = runChild({"benchmark_strip_speed", "-child", "2", "-cross", "0", "-mpts",
                                    std::to_string(m), "-swath", "500", "-density", "4"});
    std::printf("pair 2 x %.1f M points, 20 %% overlap: %s\n  process peak %.0f MB, load %.2f\n", m,
                r.ok ? r.line.c_str() : "FAILED", r.maxrss_kb / 1024.0, loadAverage());
    if (r.ok)
      std::printf("  target <= 15 s and <= 4096 MB: %s\n",
                  field(r.line, "adjust_s") <= 15.0 && r.maxrss_kb / 1024.0 <= 4096.0 ? "PASS" : "FAIL");
  }
  double prev_t = NAN, prev_n = NAN;
  for (int n : parseList(block_sizes)) {
    const double m = mpts > 0.0 ? mpts : 1.0;
    const ChildResult r =
        runChild({"benchmark_strip_speed", "-child", std::to_string(n), "-cross", std::to_string(cross),
                  "-mpts", std::to_string(m), "-swath", "200", "-density", "2"});
    const double t = field(r.line, "adjust_s");
    std::printf("block %d x %.1f M + %d cross: %s\n  process peak %.0f MB, load %.2f; time per strip %.2f s",
                n, m, cross, r.ok ? r.line.c_str() : "FAILED", r.maxrss_kb / 1024.0, loadAverage(), t / n);
    if (std::isfinite(prev_t))
      std::printf(", time ratio %.2f for strip ratio %.2f", t / prev_t, n / prev_n);
    std::printf("\n");
    if (n == 20 && r.ok)
      std::printf("  target 20 strips <= 90 s and <= 6144 MB: %s\n",
                  t <= 90.0 && r.maxrss_kb / 1024.0 <= 6144.0 ? "PASS" : "FAIL");
    prev_t = t;
    prev_n = n;
  }
  return 0;
}
