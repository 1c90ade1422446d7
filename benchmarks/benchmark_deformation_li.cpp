// benchmark_deformation_li: Li et al. (2001) Tables 2–5 analogues on the generator's Li surface
// (50 × 50 grid, spacing 100, relief 5000, noise N(0, σ = 20), deformation N(c σ, σ)).
//
//   benchmark_deformation_li -table 2|4 [-methods ls,m,md,lms,mm]
//       Table 2 / Table 4 analogue: 9 % deformed by N(200, 20) at the upper-left corner; Table 2
//       with a small transform (t = 30, −20, 15; angles ~1e-3 rad), Table 4 with 5° rotations
//       and 500-unit shifts. Prints each estimator's parameters against the truth.
//   (methods: ls, zuo, huber, m, md, lms, mm, and the LMS M-step variants lms_s0, lms_mad)
//   -v: one line per trial (error, refinement, the matching's report).
//   -refine N: rounds of the stable-part refinement (stable_refinement.h); 0 gives each
//   estimator's own answer, as in Li et al.'s tables. Default: the library's.
//   -cap 0: the M-step keeps the high-breakdown fit's own scale (no neighbour-noise cap).
//   -hold_out 0: MM's M-step over every point (no reweighting cut at 2.5 s of the start).
//   -scatter_gate R: the analysis refuses a final fit whose stable part scatters by more than
//   R x sigma_d (DeformationSettings::max_stable_scatter_ratio; 0: off, to measure the figures
//   of fits the gate would refuse). -v prints them per trial, in sigma.
//   benchmark_deformation_li -grid [-methods m,md,lms,mm] [-percents 4,9,...] [-mags 3,3.5,...]
//       [-positions upper_left,upper,middle,...|all] [-seeds N] [-first_seed S] [-full]
//       Tables 3 and 5 analogues: a trial succeeds when the recovered transform moves no grid
//       node by more than 0.5 σ from the truth. Per estimator and % column the magnitudes are
//       tried in increasing order until one reaches ≥ 90 % success (all of them with -full);
//       prints the smallest such magnitude per column (Table 5's layout), the success rate per
//       position, and the detection precision / recall of the region mask per cell (over the
//       nodes that have a residual).
//   benchmark_deformation_li -lms_speed
//       The LMS search alone: 3000 subsets of 7 on the 2500-point Li surface (40 %, 25 σ), with
//       and without the early exit, after the all-points LHD start.
//   benchmark_deformation_li -pipeline N
//       The whole analysis (default MM estimator, residual field, regions) on a Li surface of
//       N × N nodes over the same 5000 × 5000 extent (20 % deformed by 10 σ): time and peak RSS.
#include <pcl_ls3d/deformation/deformation_analysis.h>
#include <pcl_ls3d/estimators/neighbour_noise.h>
#include <pcl_ls3d/evaluation/transform_error.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/sample_consensus/subset_search.h>
#include <pcl_ls3d/synth/li_surface.h>

#include <sys/resource.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

using namespace pcl_ls3d;

namespace {

constexpr double kSigma = 20.0;
double g_grow_k = 0.0;  ///< hysteresis of the second detection score (-grow_k; default: none)
int g_refine = -1;      ///< stable-part refinement rounds (-refine; -1: the library's default)
int g_cap = -1;         ///< cap the M-step scale by the neighbour noise (-cap 0|1; -1: the library's default)
int g_block_start =
    -1;  ///< LMS, MM: the block start and the choice between starts (-block_start 0|1; -1: default)
int g_hold_out = -1;  ///< MM: points beyond 2.5 s of the start out of the M-step (-hold_out 0|1; -1: default)
bool g_verbose = false;        ///< one line per trial (-v)
double g_scatter_gate = -1.0;  ///< the analysis' stable-scatter gate (-scatter_gate R; 0 off; < 0: default)

/// Precision and recall of a region labelling against the planted patch, over observed nodes.
std::pair<double, double>
detection(const synth::LiSurface& li, const deformation::ResidualField& field, const std::vector<int>& region)
{
  std::size_t tp = 0, fp = 0, fn = 0;
  for (std::size_t i = 0; i < li.deformed.size(); ++i) {
    if (!std::isfinite(field.residual[i]))
      continue;  // no conjugate: not observable
    const bool found = region[i] > 0;
    tp += found && li.deformed[i];
    fp += found && !li.deformed[i];
    fn += !found && li.deformed[i];
  }
  return {tp + fp ? static_cast<double>(tp) / static_cast<double>(tp + fp) : 1.0,
          tp + fn ? static_cast<double>(tp) / static_cast<double>(tp + fn) : 1.0};
}

std::vector<std::string>
splitList(const std::string& text)
{
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty())
      out.push_back(item);
  return out;
}

std::vector<double>
numberList(const std::string& text)
{
  std::vector<double> out;
  for (const auto& s : splitList(text))
    out.push_back(std::stod(s));
  return out;
}

struct Trial
{
  bool usable = false;
  double error_sigma = 0.0;        ///< worst grid-node displacement against the truth [σ]
  double start_error_sigma = 0.0;  ///< the same for the high-breakdown start (LMS, MM; else 0)
  double precision = 1.0, recall = 1.0;
  double grown_precision = 1.0, grown_recall = 1.0;  ///< the same with the regions grown at -grow_k
  double scale = 0.0;
  double ms = 0.0;
  double field_noise = 0.0;     ///< σ_d of the final residual field
  double stable_scatter = 0.0;  ///< 1.4826 · med |r| of the observed points outside the regions
  double weighted_rms = 0.0;    ///< √(Σ w v² / Σ w) of the final adjustment
  double kept_mad = 0.0;        ///< 1.4826 · med |v| of its observations with weight > 0
  deformation::DeformationResult result;
};

/// σ_d of the final field and the scatter of its stable part (outside the regions).
void
measureFinalFit(const std::vector<Eigen::Vector3d>& pts, Trial& t)
{
  const deformation::ResidualField& f = t.result.field;
  t.field_noise = neighbourDifferenceScale(pts, f.residual);
  std::vector<double> outside;
  for (std::size_t i = 0; i < f.residual.size(); ++i)
    if (std::isfinite(f.residual[i]) && t.result.regions.region[i] <= 0)
      outside.push_back(std::abs(f.residual[i]));
  const AdjustmentReport& a = t.result.matching.adjustment;
  double sw = 0.0, swv2 = 0.0;
  std::vector<double> kept;
  for (std::size_t j = 0; j < a.residuals.size() && j < a.weights.size(); ++j) {
    sw += a.weights[j];
    swv2 += a.weights[j] * a.residuals[j] * a.residuals[j];
    if (a.weights[j] > 0.0)
      kept.push_back(std::abs(a.residuals[j]));
  }
  t.weighted_rms = sw > 0.0 ? std::sqrt(swv2 / sw) : 0.0;
  if (!kept.empty()) {
    auto m = kept.begin() + static_cast<std::ptrdiff_t>(kept.size() / 2);
    std::nth_element(kept.begin(), m, kept.end());
    t.kept_mad = 1.4826 * *m;
  }
  if (outside.empty())
    return;
  auto mid = outside.begin() + static_cast<std::ptrdiff_t>(outside.size() / 2);
  std::nth_element(outside.begin(), mid, outside.end());
  t.stable_scatter = 1.4826 * *mid;
}

/// A method name of robustMatching, or an LMS variant by the scale of its M-step: lms (σ* of
/// the LMS fit, default), lms_s0 (s0 of the LMS fit), lms_mad (eq. 7 on all residuals).
struct Method
{
  RobustMethod method = RobustMethod::LMS;
  LmsScale lms_scale = LmsScale::FINAL;
};

bool
parseMethod(const std::string& name, Method& m)
{
  m = Method();
  if (name == "lms_s0" || name == "lms_mad") {
    m.lms_scale = name == "lms_s0" ? LmsScale::PRELIMINARY : LmsScale::MAD;
    return true;
  }
  return parseRobustMethod(name, m.method);
}

Trial
runTrial(const synth::LiSurface& li, const Method& method)
{
  std::vector<Eigen::Vector3d> pts;
  Eigen::Matrix3Xd eval(3, static_cast<Eigen::Index>(li.mate->size()));
  for (std::size_t i = 0; i < li.mate->size(); ++i) {
    pts.push_back((*li.mate)[i].getVector3fMap().cast<double>());
    eval.col(static_cast<Eigen::Index>(i)) = pts.back();
  }
  pcl::search::KdTree<PointLiDAR>::Ptr tree(new pcl::search::KdTree<PointLiDAR>);
  tree->setInputCloud(li.reference);
  PclTargetSurface<PointLiDAR> surface(li.reference, tree);
  const ConjugateRule::Ptr rule = makeConjugateRule(ConjugateRuleType::LZD);
  std::string why;
  rule->prepare(surface, &why);
  deformation::DeformationSettings s;
  s.translation_when_undetermined = false;  // Li's analogues score the model asked for
  s.matching.method = method.method;
  s.matching.lms_scale = method.lms_scale;
  if (g_refine >= 0)
    s.refinement.max_rounds = g_refine;
  if (g_cap >= 0)
    s.matching.cap_scale_by_neighbour_noise = g_cap != 0;
  if (g_hold_out >= 0)
    s.matching.mm_hold_out_beyond_start = g_hold_out != 0;
  if (g_block_start >= 0)
    s.matching.block_start = g_block_start != 0;
  if (g_scatter_gate >= 0.0)
    s.max_stable_scatter_ratio = g_scatter_gate;
  Trial t;
  pcl::console::TicToc tt;
  tt.tic();
  t.result = deformation::analyseDeformation(pts, surface, *rule, s);
  t.ms = tt.toc();
  t.usable = t.result.ok();
  if (!t.usable) {
    t.error_sigma = std::numeric_limits<double>::infinity();
    return t;
  }
  t.scale = t.result.matching.scale;
  if (t.result.matching.subsets_drawn > 0)
    t.start_error_sigma = evaluation::computeTransformError(t.result.matching.high_breakdown_transformation,
                                                            li.truth.matrix(), eval)
                              .max /
                          kSigma;
  t.error_sigma =
      evaluation::computeTransformError(t.result.matching.adjustment.transformation, li.truth.matrix(), eval)
          .max /
      kSigma;
  std::tie(t.precision, t.recall) = detection(li, t.result.field, t.result.regions.region);
  measureFinalFit(pts, t);
  deformation::RegionSettings grown = s.regions;
  grown.grow_k = g_grow_k;
  grown.plane_axis = t.result.regions.plane_normal_axis;
  const deformation::RegionAnalysis g = deformation::analyseRegions(pts, t.result.field, grown);
  std::tie(t.grown_precision, t.grown_recall) = detection(li, t.result.field, g.region);
  return t;
}

int
tableCase(int table, const std::vector<std::string>& methods)
{
  synth::LiSurfaceSettings ls;
  ls.deformation_percent = 9.0;
  ls.deformation_c = 10.0;  // N(200, 20)
  ls.position = synth::DeformationPosition::UPPER_LEFT;
  if (table == 2) {
    Vector7d p;
    p << 30.0, -20.0, 15.0, -1.5e-3, 2e-3, 3e-3, 1.0;
    ls.truth = SimilarityTransform(p);
  }
  const synth::LiSurface li = synth::makeLiSurface(ls);
  std::printf("Table %d analogue: 9 %% (achieved %.1f %%) deformed by N(200, 20) at upper_left, sigma 20\n",
              table, li.percent);
  const Vector7d truth = li.truth.vector();
  std::printf("%-6s %9s %9s %9s %10s %10s %10s %8s %8s %7s\n", "", "tx", "ty", "tz", "phi[deg]", "omega[deg]",
              "kappa[deg]", "max[sig]", "scale", "ms");
  const double d = 180.0 / M_PI;
  std::printf("%-6s %9.2f %9.2f %9.2f %10.5f %10.5f %10.5f\n", "truth", truth[0], truth[1], truth[2],
              truth[3] * d, truth[4] * d, truth[5] * d);
  for (const auto& name : methods) {
    Method m;
    if (!parseMethod(name, m)) {
      std::fprintf(stderr, "unknown method %s\n", name.c_str());
      return 1;
    }
    const Trial t = runTrial(li, m);
    if (!t.usable) {
      std::printf("%-6s failed: %s\n", name.c_str(), t.result.matching.message.c_str());
      continue;
    }
    // Parameters of the recovered transform in the truth's convention (cloud coordinates).
    const SimilarityTransform est =
        SimilarityTransform::fromMatrix(t.result.matching.adjustment.transformation);
    const Vector7d p = est.vector();
    std::printf("%-6s %9.2f %9.2f %9.2f %10.5f %10.5f %10.5f %8.2f %8.2f %7.0f  P %.3f R %.3f\n",
                name.c_str(), p[0], p[1], p[2], p[3] * d, p[4] * d, p[5] * d, t.error_sigma, t.scale, t.ms,
                t.precision, t.recall);
  }
  return 0;
}

int
grid(const std::vector<std::string>& methods, const std::vector<double>& percents,
     const std::vector<double>& mags, const std::vector<synth::DeformationPosition>& positions, int seeds,
     int first_seed, bool full)
{
  std::printf(
      "Grid: %zu positions x %d seeds (from %d) per cell; success = max grid-node error <= 0.5 sigma\n",
      positions.size(), seeds, first_seed);
  for (const auto& name : methods) {
    Method m;
    if (!parseMethod(name, m)) {
      std::fprintf(stderr, "unknown method %s\n", name.c_str());
      return 1;
    }
    pcl::console::TicToc tt;
    tt.tic();
    std::map<double, double> smallest;  // percent -> smallest magnitude with >= 90 %
    std::printf("\n== %s ==\n", name.c_str());
    std::printf("%5s %6s %6s %6s %6s %6s %6s  per position (prec, rec: default regions; gprec, grec: regions "
                "grown at %g sigma, 0 = no hysteresis)\n",
                "%", "c", "succ", "prec", "rec", "gprec", "grec", g_grow_k);
    for (const double percent : percents) {
      smallest[percent] = NAN;
      for (const double c : mags) {
        int ok = 0, n = 0;
        double prec = 0.0, rec = 0.0, gprec = 0.0, grec = 0.0;
        int det_n = 0;
        std::vector<int> pos_ok(positions.size(), 0);
        for (std::size_t pi = 0; pi < positions.size(); ++pi)
          for (int seed = first_seed; seed < first_seed + seeds; ++seed) {
            synth::LiSurfaceSettings ls;
            ls.deformation_percent = percent;
            ls.deformation_c = c;
            ls.position = positions[pi];
            ls.seed = static_cast<std::uint32_t>(seed);
            const synth::LiSurface li = synth::makeLiSurface(ls);
            const Trial t = runTrial(li, m);
            if (g_verbose) {
              for (const auto& c : t.result.start_choice.candidates)
                std::printf("      %s: scatter %.2f on %zu points%s\n", c.name.c_str(), c.scatter, c.outside,
                            c.usable ? "" : " (no usable fit)");
              std::printf("   %s seed %d err %.3f (start %.3f) sigma_d %.2f stable %.2f wrms %.2f kmad %.2f "
                          "hb %.2f chosen %s refine %d left %zu (%s) %s\n",
                          synth::toString(positions[pi]), seed, t.error_sigma, t.start_error_sigma,
                          t.field_noise / kSigma, t.stable_scatter / kSigma, t.weighted_rms / kSigma,
                          t.kept_mad / kSigma, t.result.matching.high_breakdown_scale / kSigma,
                          t.result.start_choice.chosen.c_str(), t.result.refinement.rounds,
                          t.result.refinement.left_out, t.result.refinement.stopped.c_str(),
                          (t.result.matching.brief() + " / " + t.result.matching.message).c_str());
            }
            ++n;
            if (t.usable && t.error_sigma <= 0.5) {
              ++ok;
              ++pos_ok[pi];
              prec += t.precision;
              rec += t.recall;
              gprec += t.grown_precision;
              grec += t.grown_recall;
              ++det_n;
            }
          }
        const double rate = static_cast<double>(ok) / n;
        std::printf("%5.0f %6.1f %6.2f %6.3f %6.3f %6.3f %6.3f ", percent, c, rate,
                    det_n ? prec / det_n : NAN, det_n ? rec / det_n : NAN, det_n ? gprec / det_n : NAN,
                    det_n ? grec / det_n : NAN);
        for (std::size_t pi = 0; pi < positions.size(); ++pi)
          std::printf(" %s %d/%d", synth::toString(positions[pi]), pos_ok[pi], seeds);
        std::printf("\n");
        std::fflush(stdout);
        if (rate >= 0.9 && std::isnan(smallest[percent]))
          smallest[percent] = c;
        if (rate >= 0.9 && !full)
          break;
      }
    }
    std::printf("Table 5 row %s (smallest c reaching >= 90 %%):", name.c_str());
    for (const double percent : percents) {
      if (std::isnan(smallest[percent]))
        std::printf("  %g%%: >%g", percent, mags.back());
      else
        std::printf("  %g%%: %g", percent, smallest[percent]);
    }
    std::printf("   (%.0f s)\n", tt.toc() / 1000.0);
  }
  return 0;
}

int
lmsSpeed()
{
  synth::LiSurfaceSettings ls;
  ls.deformation_percent = 40.0;
  ls.deformation_c = 25.0;
  const synth::LiSurface li = synth::makeLiSurface(ls);
  std::vector<Eigen::Vector3d> pts;
  for (const auto& p : *li.mate)
    pts.push_back(p.getVector3fMap().cast<double>());
  pcl::search::KdTree<PointLiDAR>::Ptr tree(new pcl::search::KdTree<PointLiDAR>);
  tree->setInputCloud(li.reference);
  PclTargetSurface<PointLiDAR> surface(li.reference, tree);
  const ConjugateRule::Ptr rule = makeConjugateRule(ConjugateRuleType::LZD);
  std::string why;
  rule->prepare(surface, &why);
  RobustMatchingSettings ls_settings;
  ls_settings.method = RobustMethod::LEAST_SQUARES;
  const RobustMatchingReport start =
      robustMatching(pts, {}, surface, *rule, ls_settings, Eigen::Matrix4d::Identity());
  LinearizedMatching lin;
  if (!lin.reset(pts, surface, *rule, AdjustmentSettings::rigid6(), start.adjustment.transformation, &why)) {
    std::fprintf(stderr, "%s\n", why.c_str());
    return 1;
  }
  for (const bool early : {true, false}) {
    SubsetSearchSettings s;
    s.subsets = 3000;
    s.early_exit = early;
    pcl::console::TicToc tt;
    double best = 1e30;
    SubsetSearchResult r;
    for (int rep = 0; rep < 5; ++rep) {
      tt.tic();
      r = leastMedianOfSquares(lin, s);
      best = std::min(best, tt.toc());
    }
    std::printf("LMS 3000 subsets of 7 on %zu observations, early exit %s: best of 5 %.1f ms (med v^2 %.1f, "
                "valid %d)\n",
                lin.size(), early ? "on " : "off", best, r.criterion, r.valid);
  }
  return 0;
}

int
pipeline(int n)
{
  synth::LiSurfaceSettings ls;
  ls.grid_size = n;
  ls.spacing = 5000.0 / n;
  ls.deformation_percent = 20.0;
  ls.deformation_c = 10.0;
  const synth::LiSurface li = synth::makeLiSurface(ls);
  pcl::console::TicToc tt;
  tt.tic();
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(li.mate->size());
  for (const auto& p : *li.mate)
    pts.push_back(p.getVector3fMap().cast<double>());
  pcl::search::KdTree<PointLiDAR>::Ptr tree(new pcl::search::KdTree<PointLiDAR>);
  tree->setInputCloud(li.reference);
  PclTargetSurface<PointLiDAR> surface(li.reference, tree);
  const ConjugateRule::Ptr rule = makeConjugateRule(ConjugateRuleType::LZD);
  std::string why;
  rule->prepare(surface, &why);
  deformation::DeformationSettings settings;
  settings.translation_when_undetermined = false;  // scored against a truth with rotations
  if (g_refine >= 0)
    settings.refinement.max_rounds = g_refine;
  const deformation::DeformationResult r = deformation::analyseDeformation(pts, surface, *rule, settings);
  const double ms = tt.toc();
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  Eigen::Matrix3Xd eval(3, static_cast<Eigen::Index>(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i)
    eval.col(static_cast<Eigen::Index>(i)) = pts[i];
  const double err = r.ok() ? evaluation::computeTransformError(r.matching.adjustment.transformation,
                                                                li.truth.matrix(), eval)
                                      .max /
                                  kSigma
                            : NAN;
  std::printf(
      "%d x %d = %zu points per epoch: %.2f s (kd-tree, matching, residuals, regions), peak RSS %.0f MB, "
      "max error %.2f sigma, %.1f %% deformed (planted %.1f %%), %s\n",
      n, n, pts.size(), ms / 1000.0, ru.ru_maxrss / 1024.0, err, r.regions.percent_deformed, li.percent,
      r.matching.brief().c_str());
  if (!r.ok()) {
    std::printf("no usable estimate: %s\n", r.matching.message.c_str());
    return 1;
  }
  // Which nodes have a residual (a conjugate on the reference), inside and outside the patch.
  std::size_t in = 0, in_observed = 0, out = 0, out_observed = 0;
  for (std::size_t i = 0; i < li.deformed.size(); ++i) {
    const bool observed = std::isfinite(r.field.residual[i]);
    (li.deformed[i] ? in : out) += 1;
    (li.deformed[i] ? in_observed : out_observed) += observed;
  }
  std::printf("observed: %zu of %zu deformed nodes (%.1f %%), %zu of %zu stable nodes (%.1f %%)\n",
              in_observed, in,
              100.0 * static_cast<double>(in_observed) / static_cast<double>(std::max<std::size_t>(in, 1)),
              out_observed, out,
              100.0 * static_cast<double>(out_observed) / static_cast<double>(std::max<std::size_t>(out, 1)));
  return 0;
}

}  // namespace

int
main(int argc, char** argv)
{
  std::string methods = "ls,m,md,lms,mm", percents = "4,9,16,20,22,25,30,36,42,46,49",
              mags = "3,3.5,4,4.5,5,7,10,15,25,50,100", positions = "upper_left,upper,middle";
  int table = 0, seeds = 10, first_seed = 1;
  pcl::console::parse_argument(argc, argv, "-table", table);
  pcl::console::parse_argument(argc, argv, "-methods", methods);
  pcl::console::parse_argument(argc, argv, "-percents", percents);
  pcl::console::parse_argument(argc, argv, "-mags", mags);
  pcl::console::parse_argument(argc, argv, "-positions", positions);
  pcl::console::parse_argument(argc, argv, "-seeds", seeds);
  pcl::console::parse_argument(argc, argv, "-first_seed", first_seed);
  pcl::console::parse_argument(argc, argv, "-grow_k", g_grow_k);
  pcl::console::parse_argument(argc, argv, "-refine", g_refine);
  pcl::console::parse_argument(argc, argv, "-cap", g_cap);
  pcl::console::parse_argument(argc, argv, "-hold_out", g_hold_out);
  pcl::console::parse_argument(argc, argv, "-block_start", g_block_start);
  pcl::console::parse_argument(argc, argv, "-scatter_gate", g_scatter_gate);
  g_verbose = pcl::console::find_switch(argc, argv, "-v");
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  int pipeline_n = 0;
  pcl::console::parse_argument(argc, argv, "-pipeline", pipeline_n);
  if (pcl::console::find_switch(argc, argv, "-lms_speed"))
    return lmsSpeed();
  if (pipeline_n > 5000) {  // N is the grid's side: N × N points per epoch
    std::fprintf(stderr, "-pipeline N is the grid's side (N x N points per epoch), at most 5000; got %d\n",
                 pipeline_n);
    return 1;
  }
  if (pipeline_n > 0)
    return pipeline(pipeline_n);
  if (table == 2 || table == 4)
    return tableCase(table, splitList(methods));
  if (pcl::console::find_switch(argc, argv, "-grid")) {
    std::vector<synth::DeformationPosition> pos;
    if (positions == "all")
      positions = "upper_left,upper,upper_right,left,middle,right,lower_left,lower,lower_right";
    for (const auto& p : splitList(positions)) {
      synth::DeformationPosition dp;
      if (!synth::parseDeformationPosition(p, dp)) {
        std::fprintf(stderr, "unknown position %s\n", p.c_str());
        return 1;
      }
      pos.push_back(dp);
    }
    return grid(splitList(methods), numberList(percents), numberList(mags), pos, seeds, first_seed,
                pcl::console::find_switch(argc, argv, "-full"));
  }
  std::fprintf(stderr,
               "usage: %s -table 2|4 [-methods ...] | -grid [-methods ...] [-percents ...] "
               "[-mags ...] [-positions ...|all] [-seeds N] [-full]\n",
               argv[0]);
  return 1;
}
