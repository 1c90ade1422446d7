#include <pcl_ls3d/strips/strip_plan.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace strips {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double
radiusOf(const Strip& s)
{
  double r2 = 0.0;
  for (const auto& p : s.points)
    r2 = std::max(r2, static_cast<double>(p.head<2>().squaredNorm()));
  return std::sqrt(r2);
}

// Reference strips: the user's, else per connected part the strip with the largest overlap area.
bool
chooseDatum(StripPlan& plan, std::string& error)
{
  const StripAdjustmentSettings& s = plan.settings;
  const std::size_t n = plan.strips.size();
  if (s.soft_datum) {
    plan.notes.push_back("soft datum: every strip observed at the identity (no strip fixed)");
    return true;
  }
  for (int r : s.reference_strips) {
    if (r < 0 || static_cast<std::size_t>(r) >= n) {
      error = "reference strip index " + std::to_string(r) + " is out of range";
      return false;
    }
    plan.strips[static_cast<std::size_t>(r)].reference = true;
  }
  std::vector<double> area(n, 0.0);
  for (const Overlap& o : plan.overlaps)
    if (o.used) {
      area[static_cast<std::size_t>(o.i)] += o.area;
      area[static_cast<std::size_t>(o.j)] += o.area;
    }
  int parts = 0;
  for (const PlannedStrip& p : plan.strips)
    parts = std::max(parts, p.part + 1);
  for (int part = 0; part < parts; ++part) {
    int best = -1;
    bool has_reference = false;
    for (std::size_t k = 0; k < n; ++k)
      if (plan.strips[k].part == part) {
        has_reference = has_reference || plan.strips[k].reference;
        if (best < 0 || area[k] > area[static_cast<std::size_t>(best)])
          best = static_cast<int>(k);
      }
    if (has_reference || best < 0)
      continue;
    plan.strips[static_cast<std::size_t>(best)].reference = true;
    plan.notes.push_back(
        "reference strip " + plan.strips[static_cast<std::size_t>(best)].name +
        (s.reference_strips.empty()
             ? " (largest overlap area"
             : " (added: no reference in its part of the block, largest overlap area") +
        (parts > 1 ? ", part " + std::to_string(part + 1) + " of " + std::to_string(parts) + ")" : ")"));
  }
  return true;
}

}  // namespace

std::vector<int>
StripPlan::jobs() const
{
  std::vector<int> out;
  for (std::size_t k = 0; k < overlaps.size(); ++k)
    if (overlaps[k].used)
      out.push_back(static_cast<int>(k));
  return out;
}

std::vector<ParameterBlock>
StripPlan::initialBlocks(double soft_sigma_obs) const
{
  std::vector<ParameterBlock> blocks(strips.size());
  const Vector7d model = parameterModelWeights(settings.model);
  for (std::size_t k = 0; k < strips.size(); ++k) {
    ParameterBlock& b = blocks[k];
    b.input_origin = Eigen::Vector3d::Zero();  // points are local to o_k already
    b.output_origin = strips[k].origin;
    b.apriori_weights = model;
    if (strips[k].reference || strips[k].part < 0)
      b.apriori_weights.setConstant(kInf);
    else if (settings.soft_datum)
      for (int p = 0; p < 7; ++p)
        if (!std::isinf(b.apriori_weights[p]))
          b.apriori_weights[p] = std::pow(soft_sigma_obs / settings.soft_sigmas[p], 2);
  }
  return blocks;
}

GaussMarkovProblem
StripPlan::problem(const std::vector<ParameterBlock>& blocks) const
{
  GaussMarkovProblem p(7 * static_cast<int>(blocks.size()));
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const Eigen::Index o = 7 * static_cast<Eigen::Index>(k);
    p.current.segment<7>(o) = blocks[k].values;
    p.apriori_values.segment<7>(o) = blocks[k].apriori_values;
    p.apriori_weights.segment<7>(o) = blocks[k].apriori_weights;
    p.scaling.segment<3>(o).setOnes();
    // Rank test in "displacement at the strip's edge": angles and scale times 1 / radius.
    p.scaling.segment<4>(o + 3).setConstant(1.0 / std::max(1.0, strips[k].radius));
  }
  p.determinability_threshold = settings.adjustment.determinability_threshold;
  return p;
}

bool
makePlan(const std::vector<Strip>& strips, const StripAdjustmentSettings& settings, StripPlan& plan,
         std::string& error, Footprints* footprints_out)
{
  plan = StripPlan();
  plan.settings = settings;
  if (!settings.isValid(&error))
    return false;
  if (strips.size() < 2) {
    error = "a strip adjustment needs at least two strips (got " + std::to_string(strips.size()) + ")";
    return false;
  }
  for (const Strip& s : strips)
    if (s.observableCount() < 3) {
      error = "strip " + s.name + " has fewer than 3 observable points";
      return false;
    }
  const Footprints f = Footprints::build(strips, settings.footprint_cell);
  plan.grid = f.grid();
  const double min_area =
      settings.min_overlap_area > 0.0 ? settings.min_overlap_area : 100.0 * f.cell() * f.cell();
  plan.overlaps = findOverlaps(f, min_area);
  double sparsest = kInf;
  for (std::size_t k = 0; k < strips.size(); ++k) {
    PlannedStrip p;
    p.name = strips[k].name;
    p.point_source_id = strips[k].point_source_id;
    p.origin = strips[k].origin;
    p.points = strips[k].size();
    p.observable = strips[k].observableCount();
    p.excluded = strips[k].excluded;
    p.density = f.density(k);
    p.radius = radiusOf(strips[k]);
    p.classified = strips[k].classified();
    sparsest = std::min(sparsest, p.density);
    plan.strips.push_back(p);
  }
  const std::vector<int> parts = connectedParts(strips.size(), plan.overlaps);
  for (std::size_t k = 0; k < strips.size(); ++k)
    plan.strips[k].part = parts[k];
  if (plan.jobs().empty()) {
    error = plan.overlaps.empty() ? "no two strips overlap"
                                  : "no overlap is large enough (largest common area below the minimum)";
    return false;
  }
  for (const PlannedStrip& p : plan.strips)
    if (p.part < 0)
      plan.notes.push_back("strip " + p.name + " has no usable overlap: left unchanged");
  plan.precision_cell = settings.adjustment.precision_cell > 0.0 ? settings.adjustment.precision_cell
                                                                 : 8.0 / std::sqrt(std::max(1e-12, sparsest));
  if (!chooseDatum(plan, error))
    return false;
  if (footprints_out)
    *footprints_out = f;
  return true;
}

}  // namespace strips
}  // namespace pcl_ls3d
