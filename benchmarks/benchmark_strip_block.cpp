// benchmark_strip_block: what the simultaneous block adjustment buys, on generated blocks with
// known truth.
//   -chain: 8 parallel strips with small random errors (shift σ 0.15 m, angles σ 3e-4 rad), strip
//           1 the reference. The block adjustment (all strips at once; with C cross strips flown
//           across the row) against pairwise LS3D chained strip by strip (strip k adjusted onto
//           strip k−1 alone, the corrections composed). Prints every strip's error (mean |Δ| of
//           recovered minus true correction over its points) and the worst-strip ratio chain /
//           block, for seeds -seed .. -seed + N − 1 (-seeds N, default 5; per strip for one seed).
//           Target: median ratio ≥ 2.
//   -coverage N: N noise seeds of a 3-strip block; per parameter the share of |estimate − truth|
//           ≤ σ and ≤ 2σ, spatial-sandwich σ (reported) and formal σ0 √q_ii. Expected 68 / 95 %.
// Usage: benchmark_strip_block -chain [-cross 2] [-length 400] [-swath 160] [-density 2] [-seed 1] [-seeds 5]
//        benchmark_strip_block -coverage 100 [-length 400] [-swath 160] [-density 2]   (defaults shown)
#include "strip_bench_common.h"

#include <pcl_ls3d/stats/descriptive.h>

#include <pcl/console/parse.h>

#include <algorithm>
#include <array>
#include <cstdio>

using namespace pcl_ls3d;
using namespace strip_bench;

namespace {

synth::StripSettings
rowOfStrips(int strips, int cross, double length, double swath, double density, std::uint32_t seed)
{
  synth::StripSettings s;
  s.seed = seed;
  s.num_strips = strips;
  s.cross_strips = cross;
  s.strip_length = length;
  s.swath_width = swath;
  s.side_overlap = 0.3;
  s.density = density;
  s.noise_sigma = 0.05;
  s.shift_sigma = 0.15;
  s.angle_sigma = 3e-4;
  s.scale_sigma = 0.0;
  return s;
}

strips::StripAdjustmentSettings
rigidWithReference(int reference)
{
  strips::StripAdjustmentSettings settings;
  settings.reference_strips = {reference};
  return settings;
}

/// Strip k adjusted onto strip k−1 alone, corrections composed from strip 0 (the reference).
std::vector<Eigen::Matrix4d>
chainPairwise(const Block& b, int n, double& seconds)
{
  std::vector<Eigen::Matrix4d> T(static_cast<std::size_t>(n), Eigen::Matrix4d::Identity());
  seconds = 0.0;
  for (int k = 1; k < n; ++k) {
    const std::vector<strips::Strip> pair = {b.strips[static_cast<std::size_t>(k - 1)], b.strips[static_cast<std::size_t>(k)]};
    const Run r = adjust(pair, rigidWithReference(0));
    seconds += r.seconds;
    if (!r.ok) {
      std::printf("  pair %d-%d failed: %s\n", k, k + 1, r.error.c_str());
      continue;
    }
    T[static_cast<std::size_t>(k)] = T[static_cast<std::size_t>(k - 1)] * r.report.strips[1].transformation;
  }
  return T;
}

struct ChainResult
{
  double worst_block = 0.0, worst_chain = 0.0;

  double
  ratio() const
  {
    return worst_chain / worst_block;
  }
};

ChainResult
runChain(int cross, double length, double swath, double density, std::uint32_t seed, bool per_strip)
{
  const int n = 8;
  const Block b = makeBlock(rowOfStrips(n, cross, length, swath, density, seed));
  const Run block = adjust(b.strips, rigidWithReference(0));
  double chain_s = 0.0;
  const std::vector<Eigen::Matrix4d> chain = chainPairwise(b, n, chain_s);
  ChainResult r;
  for (int k = 1; k < n; ++k) {
    const std::size_t s = static_cast<std::size_t>(k);
    const double eb = block.ok ? displacement(b, s, block.report.strips[s].transformation, trueMatrix(b, s)).mean_norm : NAN;
    const double ec = displacement(b, s, chain[s], trueMatrix(b, s)).mean_norm;
    r.worst_block = std::max(r.worst_block, eb);
    r.worst_chain = std::max(r.worst_chain, ec);
    if (per_strip)
      std::printf("  strip %d: block mean|delta| %.4f m, chain %.4f m\n", k + 1, eb, ec);
  }
  std::printf("  seed %2u (%zu points): block %s, %d iterations, %.1f s; chain of %d pairs %.1f s; worst strip block "
              "%.4f m, chain %.4f m, ratio %.2f\n", seed, b.strips.size() * b.strips[0].size(),
              terminationTypeToString(block.report.termination), block.report.iterations, block.seconds, n - 1, chain_s,
              r.worst_block, r.worst_chain, r.ratio());
  return r;
}

/// Seeds first .. first + seeds − 1; one seed's ratio is one draw (the chain can be lucky), so
/// the target is judged on the median ratio.
void
runChains(int cross, double length, double swath, double density, int first, int seeds)
{
  std::printf("\n=== chain: 8 strips %.0f x %.0f m, 30 %% side overlap, %.1f pts/m2, noise 0.05 m, %d cross strips, "
              "seeds %d..%d (load %.2f)\n", length, swath, density, cross, first, first + seeds - 1, loadAverage());
  std::vector<double> ratios;
  for (int k = 0; k < seeds; ++k) {
    ratios.push_back(runChain(cross, length, swath, density, static_cast<std::uint32_t>(first + k), seeds == 1).ratio());
  }
  const std::size_t at_least_two = static_cast<std::size_t>(
      std::count_if(ratios.begin(), ratios.end(), [](double q) { return q >= 2.0; }));
  const double median = stats::median(ratios);
  const auto range = std::minmax_element(ratios.begin(), ratios.end());
  std::printf("  worst-strip ratio chain/block: median %.2f over %d seeds (range %.2f .. %.2f), >= 2 on %zu; "
              "target median >= 2: %s (load %.2f)\n", median, seeds, *range.first, *range.second, at_least_two,
              median >= 2.0 ? "PASS" : "FAIL", loadAverage());
}

struct Coverage
{
  std::array<int, 7> n{}, in1{}, in2{}, formal1{}, formal2{};
};

void
addStrip(const Block& b, const strips::StripResult& r, std::size_t k, Coverage& c)
{
  const Vector7d truth = trueParameters(b, k);
  for (int p = 0; p < 6; ++p) {
    const std::size_t q = static_cast<std::size_t>(p);
    const double e = std::abs(r.parameters[p] - truth[p]);
    ++c.n[q];
    c.in1[q] += e <= r.sigmas[p];
    c.in2[q] += e <= 2.0 * r.sigmas[p];
    c.formal1[q] += e <= r.sigmas_formal[p];
    c.formal2[q] += e <= 2.0 * r.sigmas_formal[p];
  }
}

void
runCoverage(int seeds, double length, double swath, double density)
{
  Coverage c;
  int failed = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int seed = 1; seed <= seeds; ++seed) {
    synth::StripSettings s = rowOfStrips(3, 0, length, swath, density, static_cast<std::uint32_t>(seed));
    s.shift_sigma = 0.3;
    s.angle_sigma = 5e-4;
    const Block b = makeBlock(s);
    const Run r = adjust(b.strips, rigidWithReference(0));
    if (!r.ok || !r.report.converged()) {
      ++failed;
      continue;
    }
    for (std::size_t k = 1; k < 3; ++k)
      addStrip(b, r.report.strips[k], k, c);
  }
  std::printf("\n=== coverage: %d seeds, 3 strips %.0f x %.0f m, 30 %% overlap, %.1f pts/m2, noise 0.05 m, rigid, "
              "strip 1 fixed; %d runs not converged; %.0f s (load %.2f)\n", seeds, length, swath, density, failed,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), loadAverage());
  const char* names[6] = {"tx", "ty", "tz", "phi", "omega", "kappa"};
  std::printf("  param  n    |e|<=sigma  |e|<=2sigma   (formal sigma0 sqrt(q): <=1, <=2)\n");
  int n = 0, a = 0, b2 = 0;
  for (std::size_t p = 0; p < 6; ++p) {
    const double k = c.n[p] > 0 ? 100.0 / c.n[p] : 0.0;
    std::printf("  %-6s %-4d %6.1f %%    %6.1f %%       (%5.1f %%, %5.1f %%)\n", names[p], c.n[p], k * c.in1[p],
                k * c.in2[p], k * c.formal1[p], k * c.formal2[p]);
    n += c.n[p];
    a += c.in1[p];
    b2 += c.in2[p];
  }
  std::printf("  all    %-4d %6.1f %%    %6.1f %%    (expected 68.3 %% / 95.4 %%)\n", n, 100.0 * a / std::max(n, 1),
              100.0 * b2 / std::max(n, 1));
}

}  // namespace

int
main(int argc, char** argv)
{
  int cross = 2, seed = 1, chain_seeds = 5, seeds = 0;
  double length = 400.0, swath = 160.0, density = 2.0;
  pcl::console::parse_argument(argc, argv, "-cross", cross);
  pcl::console::parse_argument(argc, argv, "-seed", seed);
  pcl::console::parse_argument(argc, argv, "-seeds", chain_seeds);
  pcl::console::parse_argument(argc, argv, "-length", length);
  pcl::console::parse_argument(argc, argv, "-swath", swath);
  pcl::console::parse_argument(argc, argv, "-density", density);
  pcl::console::parse_argument(argc, argv, "-coverage", seeds);
  std::printf("benchmark_strip_block: load %.2f\n", loadAverage());
  if (pcl::console::find_switch(argc, argv, "-chain"))
    runChains(cross, length, swath, density, seed, std::max(1, chain_seeds));
  if (seeds > 0)
    runCoverage(seeds, length, swath, density);
  return 0;
}
