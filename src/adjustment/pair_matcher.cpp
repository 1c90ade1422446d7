#include <pcl_ls3d/adjustment/pair_matcher.h>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {

namespace {
// Points per work unit: observations are gathered per chunk and concatenated in chunk order,
// so the set is ordered by source point whatever the thread schedule.
constexpr std::size_t kChunk = 2048;
}  // namespace

void
PairMatcher::reset(const std::vector<Eigen::Vector3d>& source, const TargetSurface& target,
                   const ConjugateRule& rule, double max_distance)
{
  source_ = &source;
  target_ = &target;
  rule_ = &rule;
  max_distance_ = max_distance;
  caches_.assign(source.size(), CorrespondenceCache());
  missed_.assign(source.size(), 0);
  chunks_.resize((source.size() + kChunk - 1) / kChunk);
  grid_.build(target, max_distance);
  grid_reach_ = max_distance;
}

void
PairMatcher::setReach(double max_distance)
{
  if (max_distance == max_distance_)
    return;
  max_distance_ = max_distance;
  // The grid stays conservative for any smaller reach; rebuild when it culls much less than it could.
  if (max_distance > grid_reach_ || max_distance < 0.75 * grid_reach_ || !grid_.built()) {
    grid_.build(*target_, max_distance);
    grid_reach_ = max_distance;
  }
}

void
PairMatcher::keepOnly(const std::vector<char>& keep)
{
  std::vector<Observation>& items = set_.items();
  if (keep.size() != items.size())
    return;
  std::size_t n = 0;
  for (std::size_t j = 0; j < items.size(); ++j)
    if (keep[j])
      items[n++] = items[j];
  items.resize(n);
}

void
PairMatcher::matchPoint(std::size_t p, const BlockLinearization& source_pose,
                        const BlockLinearization& target_pose, std::vector<Observation>& out)
{
  const Eigen::Vector3d query = target_pose.toInput(source_pose.toOutput((*source_)[p]));
  ConjugateObservations found;
  int count = 0;
  const int most = std::max(1, std::min(3, rule_->maxObservations()));
  if (grid_.mayOverlap(query) && rule_->findConjugate(query, *target_, max_distance_, caches_[p], found))
    for (int k = 0; k < std::min(found.count, most); ++k) {
      const ConjugateObservation& c = found.items[static_cast<std::size_t>(k)];
      if (!std::isfinite(c.distance) || !c.direction.allFinite())
        continue;
      Observation o;
      o.point = static_cast<int>(p);
      o.component = count++;
      o.direction = target_pose.directionToOutput(c.direction);
      o.distance = target_pose.identity() ? c.distance : target_pose.scale() * c.distance;
      o.foot = c.foot;
      o.surface_variance = c.variance;
      out.push_back(o);
    }
  missed_[p] = count == 0;
}

const ObservationSet&
PairMatcher::match(const BlockLinearization& source_pose, const BlockLinearization& target_pose,
                   const Sampling& sampling)
{
  source_pose_ = source_pose;
  target_pose_ = target_pose;
  const std::size_t n = source_->size();
  const std::ptrdiff_t chunks = static_cast<std::ptrdiff_t>(chunks_.size());
#pragma omp parallel for schedule(dynamic, 1) if (chunks > 1)
  for (std::ptrdiff_t c = 0; c < chunks; ++c) {
    std::vector<Observation>& out = chunks_[static_cast<std::size_t>(c)];
    out.clear();
    const std::size_t end = std::min(n, static_cast<std::size_t>(c + 1) * kChunk);
    for (std::size_t p = static_cast<std::size_t>(c) * kChunk; p < end; ++p)
      if (p % sampling.every == 0 && !(sampling.skip_missed && missed_[p]))
        matchPoint(p, source_pose, target_pose, out);
  }
  std::vector<Observation>& items = set_.items();
  std::size_t total = 0;
  for (const auto& chunk : chunks_)
    total += chunk.size();
  items.clear();
  items.reserve(total);
  for (auto& chunk : chunks_) {  // moved out and released: one copy of the set stays in memory
    items.insert(items.end(), chunk.begin(), chunk.end());
    std::vector<Observation>().swap(chunk);
  }
  return set_;
}

bool
PairMatcher::restore(State state)
{
  if (state.caches.size() != caches_.size() || state.missed.size() != missed_.size())
    return false;
  caches_ = std::move(state.caches);
  missed_ = std::move(state.missed);
  return true;
}

void
PairMatcher::freeze()
{
  for (CorrespondenceCache& c : caches_)
    c.frozen = true;
}

RowVector7d
PairMatcher::sourceRow(const Observation& o) const
{
  return source_pose_.designRow(o.direction, sourcePoint(o));
}

RowVector7d
PairMatcher::targetRow(const Observation& o) const
{
  // l = m_t u_tᵀ(y − q) with y = T_t⁻¹(x): rotations act at y, the scale at q (l / m_t = u_tᵀ(y − q)).
  const Eigen::Vector3d y = target_pose_.toInput(position(o));
  RowVector7d a = -target_pose_.designRow(o.direction, y - target_pose_.inputOrigin());
  a[SCALE] += o.distance / target_pose_.scale();
  return a;
}

Eigen::Vector3d
PairMatcher::position(const Observation& o) const
{
  return source_pose_.toOutput(sourcePoint(o));
}

}  // namespace pcl_ls3d
