#include <pcl_ls3d/adjustment/noise_floor.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/search/flann_kd_tree.h>
#include <pcl_ls3d/strips/overlap_matcher.h>

#include <pcl/search/kdtree.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace pcl_ls3d {
namespace strips {

namespace {

using Row14 = Eigen::Matrix<double, 1, 14>;
using CellMap = std::map<std::tuple<int, int, int>, PrecisionCell>;
// Observations per accumulation chunk: chunks are summed in order, so the normal equations do
// not depend on the number of threads (a distributed job reproduces them bit for bit).
constexpr std::size_t kChunk = 4096;

}  // namespace

struct OverlapMatcher::Direction
{
  const DirectionSelection& selection;
  bool forward = true;  // source is strip i
  pcl::search::KdTree<pcl::PointXYZ>::Ptr search;
  std::unique_ptr<PclTargetSurface<pcl::PointXYZ>> surface;
  PairMatcher matcher;
  ObservationWeighting weighting;
  ScaleColumnCorrection eiv;
  bool ready = false;

  explicit Direction(const DirectionSelection& s) : selection(s)
  {}

  // The design row [a_i | a_j] of observation k (with the errors-in-variables correction).
  Row14
  row(const Observation& o) const
  {
    RowVector7d as = matcher.sourceRow(o), at = matcher.targetRow(o);
    if (eiv.active()) {
      const double c = eiv.coefficient(o.direction.squaredNorm()) * o.distance;
      const double ratio = source_scale / target_scale;
      as[SCALE] -= c;
      at[SCALE] += c * ratio;
    }
    Row14 r;
    if (forward)
      r << as, at;
    else
      r << at, as;
    return r;
  }
  double source_scale = 1.0, target_scale = 1.0;
  double spacing = 1.0;  // thinning cell edge of the overlap

  const ObservationSet&
  match(const ParameterBlock& src, const ParameterBlock& tgt, const MatchInput& in,
        std::size_t coarse_observations);
  void
  addNormalEquations(const ObservationSet& set, const Eigen::VectorXd& p, PairNormalEquations& sum) const;
  void
  addPrecisionCells(const ObservationSet& set, const Eigen::VectorXd& p, double cell, CellMap& cells) const;
};

// Matches at the poses (every k-th point while coarse, about coarse_observations of them) and
// sets the errors-in-variables correction of the scale column for them.
const ObservationSet&
OverlapMatcher::Direction::match(const ParameterBlock& src, const ParameterBlock& tgt, const MatchInput& in,
                                 std::size_t coarse_observations)
{
  if (in.frozen)
    matcher.freeze();
  const std::size_t n = selection.points.size();
  PairMatcher::Sampling sampling;
  if (in.coarse && coarse_observations > 0 && n > 2 * coarse_observations)
    sampling.every = (n + coarse_observations - 1) / coarse_observations;
  const ObservationSet& set = matcher.match(BlockLinearization(src), BlockLinearization(tgt), sampling);
  if (set.empty())
    return set;
  source_scale = src.values[SCALE];
  target_scale = tgt.values[SCALE];
  double mean_u2 = 0.0;
  for (const Observation& o : set)
    mean_u2 += o.direction.squaredNorm();
  if (in.scale_free)
    eiv.update(src.values[SCALE], in.sigma0, mean_u2 / static_cast<double>(set.size()));
  else
    eiv.update(1.0, 0.0, 1.0);  // inactive
  return set;
}

// Eq. 8 per chunk, added to `sum` in chunk order.
void
OverlapMatcher::Direction::addNormalEquations(const ObservationSet& set, const Eigen::VectorXd& p,
                                              PairNormalEquations& sum) const
{
  const std::size_t chunks = (set.size() + kChunk - 1) / kChunk;
  std::vector<PairNormalEquations> part(chunks);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(chunks); ++c) {
    const std::size_t end = std::min(set.size(), static_cast<std::size_t>(c + 1) * kChunk);
    for (std::size_t k = static_cast<std::size_t>(c) * kChunk; k < end; ++k)
      part[static_cast<std::size_t>(c)].add(row(set[k]), set[k].distance, p[static_cast<Eigen::Index>(k)]);
  }
  for (const PairNormalEquations& ne : part)
    sum += ne;
}

// Precision cells (spatial_precision.h): scores p v a with v = l at the adjusted poses.
void
OverlapMatcher::Direction::addPrecisionCells(const ObservationSet& set, const Eigen::VectorXd& p, double cell,
                                             CellMap& cells) const
{
  for (std::size_t k = 0; k < set.size(); ++k) {
    const double w = p[static_cast<Eigen::Index>(k)];
    if (!(w > 0.0))
      continue;
    const Eigen::Vector3d x = matcher.position(set[k]);
    const std::tuple<int, int, int> key(static_cast<int>(std::floor(x.x() / cell)),
                                        static_cast<int>(std::floor(x.y() / cell)),
                                        static_cast<int>(std::floor(x.z() / cell)));
    PrecisionCell& pc = cells[key];
    const Row14 a = row(set[k]);
    pc.score += (w * set[k].distance) * a.transpose();
    pc.normal.selfadjointView<Eigen::Upper>().rankUpdate(a.transpose(), w);
  }
}

namespace {

// How many observations kept a weight, with their Σ p v² and Σ p σ²_surface.
void
countUsed(const ObservationSet& set, const Eigen::VectorXd& p, DirectionCounts& counts)
{
  counts.used = 0;
  for (Eigen::Index k = 0; k < p.size(); ++k)
    if (p[k] > 0.0) {
      ++counts.used;
      const Observation& o = set[static_cast<std::size_t>(k)];
      counts.vtpv += p[k] * o.distance * o.distance;
      if (std::isfinite(o.surface_variance))
        counts.surface_variance += p[k] * o.surface_variance;
    }
}

// The cells in key order, their normal matrices completed from the upper triangle.
std::vector<PrecisionCell>
completedCells(const CellMap& cells)
{
  std::vector<PrecisionCell> out;
  for (const auto& kv : cells) {
    PrecisionCell pc = kv.second;
    std::tie(pc.x, pc.y, pc.z) = kv.first;
    pc.normal.triangularView<Eigen::StrictlyLower>() = pc.normal.transpose();
    out.push_back(pc);
  }
  return out;
}

}  // namespace

bool
directionWanted(const DirectionSelection& selection, bool forward, const StripAdjustmentSettings& settings)
{
  return (forward || settings.both_directions) && selection.surface && selection.surface->size() >= 3 &&
         !selection.points.empty() && selection.points.size() >= settings.min_overlap_observations;
}

Matrix14d
OverlapMatcher::noiseFloor(const Direction& D, const ObservationSet& set, const Eigen::VectorXd& p)
{
  const double var = normalNoiseVariance(set, sequentialNeighbours(D.matcher, set, 3.0 * D.spacing));
  return pcl_ls3d::noiseFloor(set, p, var, [&D](const Observation& o) { return D.row(o); });
}

OverlapMatcher::OverlapMatcher(const OverlapSelection& selection, const ConjugateRule& rule,
                               const RobustEstimator& estimator, const StripAdjustmentSettings& settings,
                               double noise_i, double noise_j)
    : settings_(settings), rule_(rule), estimator_(estimator)
{
  const DirectionSelection* sel[2] = {&selection.forward, &selection.backward};
  const double noise[2] = {noise_i, noise_j};
  for (int d = 0; d < 2; ++d) {
    dir_[d] = std::make_unique<Direction>(*sel[d]);
    Direction& D = *dir_[d];
    D.forward = d == 0;
    D.spacing = selection.spacing > 0.0 ? selection.spacing : 1.0;
    D.eiv.setSourceNoise(noise[d]);
    if (!directionWanted(*sel[d], d == 0, settings))
      continue;
    D.search.reset(new pcl_ls3d::search::FlannKdTree<pcl::PointXYZ>);
    D.search->setInputCloud(sel[d]->surface);
    D.surface = std::make_unique<PclTargetSurface<pcl::PointXYZ>>(sel[d]->surface, D.search);
    std::string why;
    if (!const_cast<ConjugateRule&>(rule).prepare(*D.surface, &why))
      continue;
    D.matcher.reset(sel[d]->points, *D.surface, rule, settings.max_distance);
    D.ready = true;
  }
}

OverlapMatcher::~OverlapMatcher() = default;

OverlapContribution
OverlapMatcher::contribute(const ParameterBlock& block_i, const ParameterBlock& block_j, const MatchInput& in)
{
  return run(block_i, block_j, in, 0.0);
}

OverlapContribution
OverlapMatcher::evaluate(const ParameterBlock& block_i, const ParameterBlock& block_j, const MatchInput& in,
                         double cell)
{
  return run(block_i, block_j, in, cell);
}

OverlapContribution
OverlapMatcher::run(const ParameterBlock& block_i, const ParameterBlock& block_j, const MatchInput& in,
                    double cell)
{
  OverlapContribution out;
  out.i = dir_[0]->selection.source;
  out.j = dir_[0]->selection.target;
  out.iteration = in.iteration;
  CellMap cells;
  for (int d = 0; d < 2; ++d) {
    Direction& D = *dir_[d];
    DirectionCounts& counts = d == 0 ? out.forward : out.backward;
    if (!D.ready)
      continue;
    const ObservationSet& set = D.forward
                                    ? D.match(block_i, block_j, in, settings_.adjustment.coarse_observations)
                                    : D.match(block_j, block_i, in, settings_.adjustment.coarse_observations);
    counts.observations = set.size();
    if (set.empty())
      continue;
    const auto row = [&D, &set](std::size_t k) { return D.row(set[k]); };
    const Eigen::VectorXd& p = D.weighting.compute(estimator_, set, row, in.sigma0, in.qxx, in.iteration);
    counts.robust_scale = robustScale(set.distances());
    D.addNormalEquations(set, p, out.normal);
    out.noise_floor += noiseFloor(D, set, p);
    countUsed(set, p, counts);
    if (cell > 0.0)
      D.addPrecisionCells(set, p, cell, cells);
  }
  out.normal.symmetrize();
  out.cells = completedCells(cells);
  return out;
}

std::array<PairMatcher::State, 2>
OverlapMatcher::state() const
{
  return {dir_[0]->matcher.state(), dir_[1]->matcher.state()};
}

bool
OverlapMatcher::restore(std::array<PairMatcher::State, 2> state)
{
  bool ok = true;
  for (int d = 0; d < 2; ++d)
    if (dir_[d]->ready)
      ok = dir_[d]->matcher.restore(std::move(state[static_cast<std::size_t>(d)])) && ok;
  return ok;
}

double
stripNoise(const pcl::PointCloud<pcl::PointXYZ>& stable, double density)
{
  if (stable.size() < 30 || !(density > 0.0))
    return 0.0;
  std::vector<Eigen::Vector3d> pts(stable.size());
  for (std::size_t k = 0; k < stable.size(); ++k)
    pts[k] = stable[k].getVector3fMap().cast<double>();
  std::vector<int> seeds(pts.size());
  for (std::size_t k = 0; k < seeds.size(); ++k)
    seeds[k] = static_cast<int>(k);
  return estimateSurfaceNoise(pts, seeds, std::sqrt(30.0 / (M_PI * density)));
}

}  // namespace strips
}  // namespace pcl_ls3d
