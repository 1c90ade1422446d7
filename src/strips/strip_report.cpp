// The report of a strip block adjustment from the stages' results (strip_block_adjustment.h).
#include <pcl_ls3d/estimators/robust_estimator.h>
#include <pcl_ls3d/stats/descriptive.h>
#include <pcl_ls3d/strips/block_precision.h>
#include <pcl_ls3d/strips/model_adequacy.h>
#include <pcl_ls3d/strips/strip_block_adjustment.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

namespace pcl_ls3d {
namespace strips {

namespace {

const char* const kParameterNames[7] = {"tx", "ty", "tz", "phi", "omega", "kappa", "m"};

const char*
ruleName(ConjugateRuleType r)
{
  return r == ConjugateRuleType::LND ? "LND" : r == ConjugateRuleType::LZD ? "LZD" : "ICP";
}

Eigen::Matrix4d
fileTransformation(const Eigen::Matrix4d& block, const Eigen::Vector3d& origin)
{
  Eigen::Matrix4d in = Eigen::Matrix4d::Identity(), out = Eigen::Matrix4d::Identity();
  in.topRightCorner<3, 1>() = -origin;
  out.topRightCorner<3, 1>() = origin;
  return out * block * in;
}

// Covariance behind the σ: the spatial sandwich from the final pass, or σ0² Qxx.
Eigen::MatrixXd
covarianceOf(const StripPlan& plan, const BlockState& state,
             const std::vector<OverlapContribution>& final_pass, std::string& model)
{
  model = "formal (eq. 14)";
  Eigen::MatrixXd C = state.sigma0 * state.sigma0 * state.qxx;
  bool cells = false;
  for (const OverlapContribution& c : final_pass)
    cells = cells || !c.cells.empty();
  if (!plan.settings.adjustment.spatial_precision || !cells || state.redundancy <= 0)
    return C;
  const GaussMarkovProblem problem = plan.problem(state.blocks(plan));
  C = blockSandwichCovariance(final_pass, state.qxx, state.sigma0, problem.apriori_weights,
                              state.determinable);
  char buf[96];
  std::snprintf(buf, sizeof(buf), "spatial sandwich, cell %.3g", plan.precision_cell);
  model = buf;
  return C;
}

StripResult
stripResult(const StripPlan& plan, const BlockState& state, const Eigen::MatrixXd& C, std::size_t k,
            std::string& undeterminable)
{
  const PlannedStrip& p = plan.strips[k];
  StripResult r;
  r.name = p.name;
  r.point_source_id = p.point_source_id;
  r.origin = plan.block_origin + p.origin;
  r.points = p.points;
  r.observable = p.observable;
  r.excluded = p.excluded;
  r.reference = p.reference;
  r.adjusted = p.part >= 0;
  r.parameters = state.values[k];
  std::string flags;
  for (int q = 0; q < 7; ++q) {
    const Eigen::Index g = 7 * static_cast<Eigen::Index>(k) + q;
    const std::size_t gs = static_cast<std::size_t>(g);
    r.fixed[static_cast<std::size_t>(q)] = gs < state.fixed.size() && state.fixed[gs];
    r.determinable[static_cast<std::size_t>(q)] = gs < state.determinable.size() && state.determinable[gs];
    if (r.fixed[static_cast<std::size_t>(q)])
      continue;
    if (!r.determinable[static_cast<std::size_t>(q)]) {
      r.sigmas[q] = r.sigmas_formal[q] = std::numeric_limits<double>::infinity();
      flags += std::string(flags.empty() ? "" : ", ") + kParameterNames[q];
      continue;
    }
    r.sigmas[q] = std::sqrt(std::max(0.0, C(g, g)));
    r.sigmas_formal[q] = state.sigma0 * std::sqrt(std::max(0.0, state.qxx(g, g)));
  }
  if (!flags.empty()) {
    r.note = "undeterminable from its overlaps (held at their start values): " + flags;
    undeterminable += (undeterminable.empty() ? "" : "; ") + p.name + ": " + flags;
  }
  if (!r.adjusted)
    r.note = "no usable overlap: left unchanged";
  else if (r.reference)
    r.note = "reference (fixed)";
  std::vector<ParameterBlock> blocks = state.blocks(plan);
  r.transformation = fileTransformation(blockTransformation(blocks[k]), plan.block_origin);
  return r;
}

// The floor an overlap's discrepancies can reach: the larger own noise of its two strips.
double
ownNoise(const OverlapResult& o)
{
  return std::max(o.noise_i.sigma_mad, o.noise_j.sigma_mad);
}

OverlapResult
overlapResult(const Overlap& o, const OverlapContribution* c, const OverlapSamples* s)
{
  OverlapResult r;
  r.i = o.i;
  r.j = o.j;
  r.area = o.area;
  r.common_cells = o.common_cells;
  r.points_i = o.points_i;
  r.points_j = o.points_j;
  r.used = o.used;
  r.skip_reason = o.skip_reason;
  if (c) {
    r.spacing = c->spacing;
    r.observations = c->forward.observations + c->backward.observations;
    r.used_observations = c->forward.used + c->backward.used;
    r.sigma0 =
        r.used_observations ? std::sqrt((c->forward.vtpv + c->backward.vtpv) / r.used_observations) : 0.0;
    r.sigma_surface = r.used_observations
                          ? std::sqrt((c->forward.surface_variance + c->backward.surface_variance) /
                                      static_cast<double>(r.used_observations))
                          : 0.0;
  }
  if (s) {
    r.before = discrepancyStatistics(s->before.value);
    r.after = discrepancyStatistics(s->after.value);
    r.noise_i = discrepancyStatistics(s->noise[0].value);
    r.noise_j = discrepancyStatistics(s->noise[1].value);
    r.asked = askedTranslation(s->after, kAskedWithinNoise * ownNoise(r));
  }
  return r;
}

bool
evaluated(const OverlapResult& o)
{
  return o.used && o.before.count > 0 && o.after.count > 0 && o.noise_i.count > 0 && o.noise_j.count > 0;
}

// An adjustment that moves a strip (at its edge) by more than the strips' own noise must show it
// in the data: when the normal discrepancies' σMAD grew on more than half of the used overlaps,
// the corrections are not confirmed. Empty when confirmed.
std::string
spreadNotConfirmed(const StripAdjustmentReport& report, const StripPlan& plan)
{
  std::size_t used = 0, grew = 0;
  std::vector<double> noise;
  for (const OverlapResult& o : report.overlaps) {
    if (!evaluated(o))
      continue;
    ++used;
    grew += o.after.sigma_mad > o.before.sigma_mad ? 1 : 0;
    noise.push_back(ownNoise(o));
  }
  // How far a correction moves a strip at its edge (radius r from its origin): the shift, plus
  // r times the rotation and the scale change.
  double moved = 0.0;
  for (std::size_t k = 0; k < report.strips.size() && k < plan.strips.size(); ++k) {
    const Vector7d& p = report.strips[k].parameters;
    const double turn = p.segment<3>(PHI).norm() + std::abs(p[SCALE] - 1.0);
    moved = std::max(moved, p.head<3>().norm() + plan.strips[k].radius * turn);
  }
  if (used == 0 || 2 * grew <= used)
    return {};
  const double own_noise = stats::medianHigh(std::move(noise));
  if (!(moved > own_noise))
    return {};
  char buf[320];
  std::snprintf(buf, sizeof(buf),
                "the corrections move a strip by %.3g (the strips' own noise %.3g), but the "
                "discrepancies' sigmaMAD grew on %zu of %zu overlaps",
                moved, own_noise, grew, used);
  return buf;
}

// After a right adjustment two strips meet: the median normal discrepancy of an overlap is ~0
// (its standard error σ/√n is well below a millimetre). A rule that stopped in a local minimum
// (ICP's closest points on flat ground far from the truth) can leave a spread at the noise
// level but an offset: more than a quarter of the strips' own noise is not confirmed.
std::string
offsetNotConfirmed(const StripAdjustmentReport& report)
{
  const double kMaxOffset = 0.25;  // × the larger own noise of the two strips
  for (const OverlapResult& o : report.overlaps) {
    if (!evaluated(o))
      continue;
    const double own_noise = ownNoise(o);
    if (!(std::abs(o.after.p50) > kMaxOffset * own_noise))
      continue;
    char buf[320];
    std::snprintf(buf, sizeof(buf),
                  "after the corrections %s and %s are still offset by %.3g along the surface "
                  "normals (median of %zu discrepancies; the strips' own noise %.3g)",
                  report.strips[static_cast<std::size_t>(o.i)].name.c_str(),
                  report.strips[static_cast<std::size_t>(o.j)].name.c_str(), o.after.p50, o.after.count,
                  own_noise);
    return buf;
  }
  return {};
}

// A rule other than LND (ICP's closest points, LZD's heights) converges where its own
// observations are at rest; a right answer is also where LND's distances are: the translation
// they still ask for stays within noise. Far from the truth on flat ground ICP stops where the
// ground agrees and the edges do not, and the edges ask for the rest: a move larger than the
// strips' own noise that the values determine well (more than kMaxAskedSigmas of its σ for
// independent values; neighbouring values are correlated, so the honest σ is 2–3× larger) is
// not confirmed. On real blocks the LND and LZD results still ask for up to 0.6 × the noise at
// up to 14 σ (the plain mean here is not the adjustment's robust one), sparse ones for up to
// 4.4 × the noise at 4.5 σ (docs/BENCHMARKS.md).
std::string
lndNotAtRest(const StripAdjustmentReport& report, const StripPlan& plan)
{
  const double kMaxAskedSigmas = 10.0, kMaxAskedNoise = 1.0;
  if (plan.settings.rule == ConjugateRuleType::LND)
    return {};
  for (const OverlapResult& o : report.overlaps) {
    if (!evaluated(o) || o.asked.count == 0)
      continue;
    const double own_noise = ownNoise(o);
    const Eigen::Vector3d z = o.asked.t.cwiseAbs().cwiseQuotient(o.asked.sigma.cwiseMax(1e-12));
    if (!(z.maxCoeff() > kMaxAskedSigmas && o.asked.t.norm() > kMaxAskedNoise * own_noise))
      continue;
    char buf[320];
    std::snprintf(buf, sizeof(buf),
                  "after the corrections LND's distances between %s and %s still ask for a move of "
                  "(%.3g, %.3g, %.3g), %.0f times its sigma (the strips' own noise %.3g): the %s "
                  "result is not where the surfaces meet",
                  report.strips[static_cast<std::size_t>(o.i)].name.c_str(),
                  report.strips[static_cast<std::size_t>(o.j)].name.c_str(), o.asked.t.x(), o.asked.t.y(),
                  o.asked.t.z(), z.maxCoeff(), own_noise, report.rule.c_str());
    return buf;
  }
  return {};
}

// Corrections the discrepancies do not confirm make the result UNRELIABLE (the estimate stays in
// the report, with the reason).
void
confirmByDiscrepancies(StripAdjustmentReport& report, const StripPlan& plan)
{
  if (report.termination != TerminationType::CONVERGED &&
      report.termination != TerminationType::MAX_ITERATIONS)
    return;
  std::string why = spreadNotConfirmed(report, plan);
  if (why.empty())
    why = offsetNotConfirmed(report);
  if (why.empty())
    why = lndNotAtRest(report, plan);
  if (why.empty())
    return;
  report.termination = TerminationType::UNRELIABLE;
  report.message += std::string(report.message.empty() ? "" : "; ") + "NOT CONFIRMED: " + why +
                    ": check before applying them";
}

}  // namespace

StripAdjustmentReport
makeReport(const StripPlan& plan, const BlockState& state, const std::vector<OverlapContribution>& final_pass,
           const std::vector<OverlapSamples>& samples)
{
  StripAdjustmentReport report;
  const StripAdjustmentSettings& s = plan.settings;
  report.termination = state.termination;
  report.message = state.message;
  report.iterations = state.iteration;
  report.sigma0 = state.sigma0;
  report.redundancy = state.redundancy;
  report.observations = state.observations;
  report.unknowns = static_cast<int>(std::count(state.determinable.begin(), state.determinable.end(), true));
  report.rule = ruleName(s.rule);
  report.estimator = makeRobustEstimator(s.estimator)->name();
  report.model = parameterModelName(s.model);
  report.block_origin = plan.block_origin;
  report.footprint_cell = plan.grid.cell;
  report.log = state.log;
  report.notes = plan.notes;
  report.covariance = covarianceOf(plan, state, final_pass, report.precision_model);
  std::string undeterminable;
  for (std::size_t k = 0; k < plan.strips.size(); ++k)
    report.strips.push_back(stripResult(plan, state, report.covariance, k, undeterminable));
  if (!undeterminable.empty() && report.observations > 0) {
    report.notes.push_back("undeterminable parameters: " + undeterminable);
    report.message +=
        std::string(report.message.empty() ? "" : "; ") + "undeterminable parameters: " + undeterminable;
  }
  for (std::size_t k = 0; k < plan.overlaps.size(); ++k) {
    const OverlapContribution* c = nullptr;
    for (const OverlapContribution& f : final_pass)
      if (f.overlap == static_cast<int>(k))
        c = &f;
    report.overlaps.push_back(overlapResult(plan.overlaps[k], c, k < samples.size() ? &samples[k] : nullptr));
  }
  confirmByDiscrepancies(report, plan);
  testHeldOutParameters(plan, state, final_pass, report);
  confirmModel(report);
  return report;
}

}  // namespace strips
}  // namespace pcl_ls3d
