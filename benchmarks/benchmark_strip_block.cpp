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
//   -honesty: σ honesty and the held-out scale test (model_adequacy.h). Blocks of -strips N
//           parallel strips (default 6, strip 1 the reference), with a rigid truth and with
//           per-strip scales of σ -scale_sigma (default 5e-5), each adjusted rigid (default) and
//           with -params 7. Per strip: error against the truth (mean |Δ| over its points) / the
//           displacement σ the report's covariance propagates to the same points, and the
//           held-out scale's z and flag. Over seeds: mean ratios, verdicts, and the share of strips
//           on which the test fires (significance alone at several thresholds, and the full
//           flag at the default): on a rigid truth, its false-alarm rate.
// Usage: benchmark_strip_block -chain [-cross 2] [-length 400] [-swath 160] [-density 2] [-seed 1] [-seeds 5]
//        benchmark_strip_block -coverage 100 [-length 400] [-swath 160] [-density 2]   (defaults shown)
//        benchmark_strip_block -honesty [-strips 6] [-length 400] [-swath 160] [-density 2] [-seed 1] [-seeds 5]
//                              [-scale_sigma 5e-5] [-truth both|rigid|scaled] [-models both|6|7] [-buildings 1] [-relief 10] [-rule lnd]
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
    const std::vector<strips::Strip> pair = {b.strips[static_cast<std::size_t>(k - 1)],
                                             b.strips[static_cast<std::size_t>(k)]};
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
    const double eb =
        block.ok ? displacement(b, s, block.report.strips[s].transformation, trueMatrix(b, s)).mean_norm
                 : NAN;
    const double ec = displacement(b, s, chain[s], trueMatrix(b, s)).mean_norm;
    r.worst_block = std::max(r.worst_block, eb);
    r.worst_chain = std::max(r.worst_chain, ec);
    if (per_strip)
      std::printf("  strip %d: block mean|delta| %.4f m, chain %.4f m\n", k + 1, eb, ec);
  }
  std::printf(
      "  seed %2u (%zu points): block %s, %d iterations, %.1f s; chain of %d pairs %.1f s; worst strip block "
      "%.4f m, chain %.4f m, ratio %.2f\n",
      seed, b.strips.size() * b.strips[0].size(), terminationTypeToString(block.report.termination),
      block.report.iterations, block.seconds, n - 1, chain_s, r.worst_block, r.worst_chain, r.ratio());
  return r;
}

/// Seeds first .. first + seeds − 1; one seed's ratio is one draw (the chain can be lucky), so
/// the target is judged on the median ratio.
void
runChains(int cross, double length, double swath, double density, int first, int seeds)
{
  std::printf(
      "\n=== chain: 8 strips %.0f x %.0f m, 30 %% side overlap, %.1f pts/m2, noise 0.05 m, %d cross strips, "
      "seeds %d..%d (load %.2f)\n",
      length, swath, density, cross, first, first + seeds - 1, loadAverage());
  std::vector<double> ratios;
  for (int k = 0; k < seeds; ++k) {
    ratios.push_back(
        runChain(cross, length, swath, density, static_cast<std::uint32_t>(first + k), seeds == 1).ratio());
  }
  const std::size_t at_least_two = static_cast<std::size_t>(
      std::count_if(ratios.begin(), ratios.end(), [](double q) { return q >= 2.0; }));
  const double median = stats::median(ratios);
  const auto range = std::minmax_element(ratios.begin(), ratios.end());
  std::printf("  worst-strip ratio chain/block: median %.2f over %d seeds (range %.2f .. %.2f), >= 2 on %zu; "
              "target median >= 2: %s (load %.2f)\n",
              median, seeds, *range.first, *range.second, at_least_two, median >= 2.0 ? "PASS" : "FAIL",
              loadAverage());
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
  std::printf(
      "\n=== coverage: %d seeds, 3 strips %.0f x %.0f m, 30 %% overlap, %.1f pts/m2, noise 0.05 m, rigid, "
      "strip 1 fixed; %d runs not converged; %.0f s (load %.2f)\n",
      seeds, length, swath, density, failed,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), loadAverage());
  const char* names[6] = {"tx", "ty", "tz", "phi", "omega", "kappa"};
  std::printf("  param  n    |e|<=sigma  |e|<=2sigma   (formal sigma0 sqrt(q): <=1, <=2)\n");
  int n = 0, a = 0, b2 = 0;
  for (std::size_t p = 0; p < 6; ++p) {
    const double k = c.n[p] > 0 ? 100.0 / c.n[p] : 0.0;
    std::printf("  %-6s %-4d %6.1f %%    %6.1f %%       (%5.1f %%, %5.1f %%)\n", names[p], c.n[p],
                k * c.in1[p], k * c.in2[p], k * c.formal1[p], k * c.formal2[p]);
    n += c.n[p];
    a += c.in1[p];
    b2 += c.in2[p];
  }
  std::printf("  all    %-4d %6.1f %%    %6.1f %%    (expected 68.3 %% / 95.4 %%)\n", n,
              100.0 * a / std::max(n, 1), 100.0 * b2 / std::max(n, 1));
}

// --- honesty ---------------------------------------------------------------------------------

struct HonestySettings
{
  int strips = 6, first = 1, seeds = 5;
  double length = 400.0, swath = 160.0, density = 2.0, scale_sigma = 5e-5;
  bool rigid_truth = true, scaled_truth = true, rigid_model = true, free_model = true;
  bool buildings = true;
  double relief = 10.0;
  ConjugateRuleType rule = ConjugateRuleType::LND;
};

// What one (truth, model) pair gathers over the seeds.
struct HonestyTally
{
  std::vector<double> ratios, z;
  int strips = 0, flagged = 0, converged = 0, not_confirmed = 0, other = 0;
};

void
tallyRun(const Block& b, const Run& run, bool rigid, std::uint32_t seed, HonestyTally& t)
{
  if (!run.ok) {
    ++t.other;
    std::printf("    seed %u: failed: %s\n", seed, run.error.c_str());
    return;
  }
  const strips::StripAdjustmentReport& r = run.report;
  const TerminationType term = r.termination;
  (term == TerminationType::CONVERGED    ? t.converged
   : term == TerminationType::UNRELIABLE ? t.not_confirmed
                                         : t.other)++;
  std::string line;
  for (std::size_t k = 1; k < r.strips.size(); ++k) {
    const double error = displacement(b, k, r.strips[k].transformation, trueMatrix(b, k)).mean_norm;
    const double sigma = displacementSigma(b, r, k);
    t.ratios.push_back(error / sigma);
    char buf[160];
    std::snprintf(buf, sizeof(buf), " %zu:%.1f/%.1fcm=%.2f", k + 1, 100 * error, 100 * sigma, error / sigma);
    line += buf;
    if (rigid && !r.strips[k].held_out.empty()) {
      const strips::HeldOutParameter& h = r.strips[k].held_out[0];
      t.z.push_back(h.z);
      ++t.strips;
      t.flagged += h.flagged;
      std::snprintf(buf, sizeof(buf), "(z%+.1f,%+.0fppm,%.1fcm%s)", h.z, 1e6 * h.estimate, 100 * h.effect,
                    h.flagged ? ",FLAG" : "");
      line += buf;
    }
  }
  std::printf("    seed %2u %s %-11s %.0f s:%s\n", seed, rigid ? "rigid" : "7par ",
              terminationTypeToString(term), run.seconds, line.c_str());
}

void
printTally(const char* truth, const char* model, const HonestyTally& t)
{
  if (t.ratios.empty())
    return;
  const auto range = std::minmax_element(t.ratios.begin(), t.ratios.end());
  double mean = 0.0;
  for (double q : t.ratios)
    mean += q;
  mean /= static_cast<double>(t.ratios.size());
  std::printf("  %s truth, %s: error/sigma mean %.2f, median %.2f, range %.2f .. %.2f over %zu strips; "
              "CONVERGED %d, NOT CONFIRMED %d, other %d\n",
              truth, model, mean, stats::median(t.ratios), *range.first, *range.second, t.ratios.size(),
              t.converged, t.not_confirmed, t.other);
  if (t.z.empty())
    return;
  std::string fires;
  for (double thr : {2.0, 2.5, 3.0, 3.5, 4.0}) {
    const auto n = std::count_if(t.z.begin(), t.z.end(), [thr](double z) { return std::abs(z) > thr; });
    char buf[64];
    std::snprintf(buf, sizeof(buf), " |z|>%.1f: %.1f %%", thr,
                  100.0 * static_cast<double>(n) / static_cast<double>(t.z.size()));
    fires += buf;
  }
  std::vector<double> absz;
  for (double z : t.z)
    absz.push_back(std::abs(z));
  std::printf("    held-out scale over %d strips: median |z| %.2f;%s; flagged (default) %d = %.1f %%\n",
              t.strips, stats::median(absz), fires.c_str(), t.flagged,
              100.0 * t.flagged / std::max(1, t.strips));
}

void
runHonesty(const HonestySettings& h)
{
  std::printf(
      "\n=== honesty: %d strips %.0f x %.0f m, 30 %% side overlap, %.2f pts/m2, noise 0.05 m, shifts 0.15 m, "
      "angles 3e-4, scale sigma %.1e (scaled truth), strip 1 fixed, seeds %d..%d (load %.2f)\n",
      h.strips, h.length, h.swath, h.density, h.scale_sigma, h.first, h.first + h.seeds - 1, loadAverage());
  const auto t0 = std::chrono::steady_clock::now();
  for (int scaled = 0; scaled < 2; ++scaled) {
    if ((scaled && !h.scaled_truth) || (!scaled && !h.rigid_truth))
      continue;
    HonestyTally rigid, freed;
    std::printf("  %s truth:\n", scaled ? "scaled" : "rigid");
    for (int k = 0; k < h.seeds; ++k) {
      const auto seed = static_cast<std::uint32_t>(h.first + k);
      synth::StripSettings s = rowOfStrips(h.strips, 0, h.length, h.swath, h.density, seed);
      s.scale_sigma = scaled ? h.scale_sigma : 0.0;
      s.buildings = h.buildings;
      s.relief = h.relief;
      const Block b = makeBlock(s);
      strips::StripAdjustmentSettings rigid_settings = rigidWithReference(0);
      rigid_settings.rule = h.rule;
      if (h.rigid_model)
        tallyRun(b, adjust(b.strips, rigid_settings), true, seed, rigid);
      if (h.free_model) {
        strips::StripAdjustmentSettings settings = rigid_settings;
        settings.model = ParameterModel::SIMILARITY_7;
        tallyRun(b, adjust(b.strips, settings), false, seed, freed);
      }
    }
    printTally(scaled ? "scaled" : "rigid", "rigid model", rigid);
    printTally(scaled ? "scaled" : "rigid", "-params 7", freed);
  }
  std::printf("  %.0f s (load %.2f)\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), loadAverage());
}

bool
parseHonesty(int argc, char** argv, HonestySettings& h)
{
  pcl::console::parse_argument(argc, argv, "-strips", h.strips);
  pcl::console::parse_argument(argc, argv, "-seed", h.first);
  pcl::console::parse_argument(argc, argv, "-seeds", h.seeds);
  pcl::console::parse_argument(argc, argv, "-length", h.length);
  pcl::console::parse_argument(argc, argv, "-swath", h.swath);
  pcl::console::parse_argument(argc, argv, "-density", h.density);
  pcl::console::parse_argument(argc, argv, "-scale_sigma", h.scale_sigma);
  std::string truth = "both", models = "both";
  pcl::console::parse_argument(argc, argv, "-truth", truth);
  pcl::console::parse_argument(argc, argv, "-models", models);
  h.rigid_truth = truth != "scaled";
  h.scaled_truth = truth != "rigid";
  h.rigid_model = models != "7";
  h.free_model = models != "6";
  int buildings = 1;
  pcl::console::parse_argument(argc, argv, "-buildings", buildings);
  h.buildings = buildings != 0;
  pcl::console::parse_argument(argc, argv, "-relief", h.relief);
  std::string rule;
  if (pcl::console::parse_argument(argc, argv, "-rule", rule) >= 0 && !parseConjugateRuleType(rule, h.rule))
    return false;
  return h.strips >= 2 && h.seeds >= 1;
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
  if (pcl::console::find_switch(argc, argv, "-honesty")) {
    HonestySettings h;
    if (!parseHonesty(argc, argv, h)) {
      std::fprintf(stderr, "-honesty needs -strips >= 2 and -seeds >= 1\n");
      return 1;
    }
    runHonesty(h);
  }
  return 0;
}
