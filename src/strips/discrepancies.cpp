#include <pcl_ls3d/adjustment/pair_matcher.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/rules/lnd_rule.h>
#include <pcl_ls3d/search/flann_kd_tree.h>
#include <pcl_ls3d/stats/descriptive.h>
#include <pcl_ls3d/strips/discrepancies.h>

#include <pcl/search/kdtree.h>

#include <Eigen/LU>

#include <cmath>

namespace pcl_ls3d {
namespace strips {

namespace {

// The target surface without the query point itself (leave one out): asks for one more
// neighbour and drops those at distance zero.
class LeaveOneOutSurface : public TargetSurface
{
public:
  explicit LeaveOneOutSurface(const TargetSurface& base) : base_(base)
  {}
  std::size_t
  size() const override
  {
    return base_.size();
  }
  Eigen::Vector3d
  point(int index) const override
  {
    return base_.point(index);
  }
  int
  nearestKSearch(const Eigen::Vector3d& query, int k, std::vector<int>& indices,
                 std::vector<float>& sq_dists) const override
  {
    const int found = base_.nearestKSearch(query, k + 1, indices, sq_dists);
    std::size_t w = 0;
    for (std::size_t r = 0; r < static_cast<std::size_t>(std::max(0, found)); ++r)
      if (sq_dists[r] > 0.0f) {
        indices[w] = indices[r];
        sq_dists[w] = sq_dists[r];
        ++w;
      }
    w = std::min<std::size_t>(w, static_cast<std::size_t>(k));
    indices.resize(w);
    sq_dists.resize(w);
    return static_cast<int>(w);
  }

private:
  const TargetSurface& base_;
};

struct Surface
{
  pcl::search::KdTree<pcl::PointXYZ>::Ptr search;
  std::unique_ptr<PclTargetSurface<pcl::PointXYZ>> surface;

  explicit Surface(const pcl::PointCloud<pcl::PointXYZ>::Ptr& cloud)
  {
    if (!cloud || cloud->size() < 3)
      return;
    search.reset(new pcl_ls3d::search::FlannKdTree<pcl::PointXYZ>);
    search->setInputCloud(cloud);
    surface = std::make_unique<PclTargetSurface<pcl::PointXYZ>>(cloud, search);
  }
};

// LND distances of `points` (source-local) on `target`, signed "source above target".
void
measure(const std::vector<Eigen::Vector3d>& points, const TargetSurface& target, const ParameterBlock& source,
        const ParameterBlock& target_block, double max_distance, double sign, DiscrepancySamples& out)
{
  const LndRule rule;
  PairMatcher matcher;
  matcher.reset(points, target, rule, max_distance);
  const ObservationSet& set = matcher.match(BlockLinearization(source), BlockLinearization(target_block), {});
  for (const Observation& o : set) {
    const double up = o.direction.z() >= 0.0 ? 1.0 : -1.0;
    out.xy.push_back(matcher.position(o).head<2>());
    out.value.push_back(static_cast<float>(sign * up * o.distance));
    out.normal.push_back((up * o.direction).cast<float>());
  }
}

}  // namespace

struct DiscrepancyEvaluator::Impl
{
  const OverlapSelection& selection;
  double max_distance;
  Surface on_j, on_i;  // surface of j (forward target), of i (backward target)

  Impl(const OverlapSelection& s, double d)
      : selection(s), max_distance(d), on_j(s.forward.surface), on_i(s.backward.surface)
  {}
};

DiscrepancyEvaluator::DiscrepancyEvaluator(const OverlapSelection& selection, double max_distance)
    : impl_(std::make_unique<Impl>(selection, max_distance))
{}

DiscrepancyEvaluator::~DiscrepancyEvaluator() = default;

DiscrepancySamples
DiscrepancyEvaluator::evaluate(const ParameterBlock& block_i, const ParameterBlock& block_j)
{
  DiscrepancySamples out;
  const OverlapSelection& s = impl_->selection;
  if (impl_->on_j.surface)
    measure(s.forward.points, *impl_->on_j.surface, block_i, block_j, impl_->max_distance, 1.0, out);
  if (impl_->on_i.surface)
    measure(s.backward.points, *impl_->on_i.surface, block_j, block_i, impl_->max_distance, -1.0, out);
  return out;
}

std::array<DiscrepancySamples, 2>
DiscrepancyEvaluator::ownNoise(const ParameterBlock& block_i, const ParameterBlock& block_j)
{
  std::array<DiscrepancySamples, 2> out;
  const OverlapSelection& s = impl_->selection;
  const ParameterBlock identity = ParameterBlock::fixedIdentity(Eigen::Vector3d::Zero());
  const Surface* own[2] = {&impl_->on_i, &impl_->on_j};
  const std::vector<Eigen::Vector3d>* points[2] = {&s.forward.points, &s.backward.points};
  const ParameterBlock* pose[2] = {&block_i, &block_j};
  for (int k = 0; k < 2; ++k) {
    if (!own[k]->surface)
      continue;
    const LeaveOneOutSurface loo(*own[k]->surface);
    DiscrepancySamples local;
    measure(*points[k], loo, identity, identity, impl_->max_distance, 1.0, local);
    // Positions in block coordinates under the strip's pose (the map shows them in place).
    const BlockLinearization lin(*pose[k]);
    for (std::size_t q = 0; q < local.xy.size(); ++q) {
      const Eigen::Vector3d p(local.xy[q].x(), local.xy[q].y(), 0.0);
      out[static_cast<std::size_t>(k)].xy.push_back(lin.toOutput(p).head<2>());
    }
    out[static_cast<std::size_t>(k)].value = std::move(local.value);
  }
  return out;
}

AskedTranslation
askedTranslation(const DiscrepancySamples& samples, double max_abs)
{
  AskedTranslation out;
  Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  std::vector<double> kept;
  for (std::size_t k = 0; k < samples.value.size() && k < samples.normal.size(); ++k) {
    const double v = samples.value[k];
    if (!(std::abs(v) <= max_abs))
      continue;
    const Eigen::Vector3d n = samples.normal[k].cast<double>();
    N += n * n.transpose();
    b += n * v;
    kept.push_back(v);
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(N);
  if (kept.size() < 3 || lu.rank() < 3)
    return out;
  const Eigen::Matrix3d Ni = lu.inverse();
  out.count = kept.size();
  out.t = -Ni * b;
  out.sigma = stats::mad(kept, true) * Ni.diagonal().cwiseMax(0.0).cwiseSqrt();
  return out;
}

DiscrepancyStatistics
discrepancyStatistics(const std::vector<float>& values)
{
  DiscrepancyStatistics s;
  std::vector<double> v;
  v.reserve(values.size());
  for (float x : values)
    if (std::isfinite(x))
      v.push_back(x);
  s.count = v.size();
  if (v.empty())
    return s;
  double sum = 0.0, sum2 = 0.0;
  for (double x : v) {
    sum += x;
    sum2 += x * x;
  }
  s.mean = sum / static_cast<double>(v.size());
  s.rms = std::sqrt(sum2 / static_cast<double>(v.size()));
  s.sigma_mad = stats::mad(v, true);
  const std::vector<double> q = stats::quantiles(v, {0.05, 0.16, 0.5, 0.84, 0.95});
  s.p05 = q[0];
  s.p16 = q[1];
  s.p50 = q[2];
  s.p84 = q[3];
  s.p95 = q[4];
  return s;
}

}  // namespace strips
}  // namespace pcl_ls3d
