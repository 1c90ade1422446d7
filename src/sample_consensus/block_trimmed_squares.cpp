#include <pcl_ls3d/common/voxel_index.h>
#include <pcl_ls3d/sample_consensus/block_trimmed_squares.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <utility>

namespace pcl_ls3d {

namespace {

/// The axis the observations' directions are closest to: the blocks lie in the plane across it
/// (z for LZD; for LND the surface's dominant normal). Not the box's largest projection first:
/// Li's surface has as much relief as extent. (LZD's directions are the height gradients
/// (−z_x, −z_y, 1): on steep terrain x and y weigh nearly as much as z, and z still wins.) On a
/// tie (ICP observes along x, y and z alike) the box's largest projection decides.
int
surfaceNormalAxis(const LinearizedMatching& lin)
{
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Observation& o : lin.observations())
    sum += o.direction.cwiseAbs();
  int axis = 2;
  const double largest = sum.maxCoeff(&axis);
  Eigen::Vector3d others = sum;
  others[axis] = 0.0;
  if (!(largest > (1.0 + 1e-9) * others.maxCoeff()))
    return cloudSpacing(lin.reducedPoints()).normal_axis;
  return axis;
}

/// Observations of `lin` by square blocks of the epoch's dominant plane; blocks with fewer than
/// half the median block's observations are dropped.
std::vector<std::vector<int>>
observationBlocks(const LinearizedMatching& lin, double block_spacings)
{
  const std::vector<Eigen::Vector3d>& points = lin.reducedPoints();
  const int normal = surfaceNormalAxis(lin);
  const double edge = block_spacings * cloudSpacing(points, normal).spacing;
  if (!(edge > 0.0))
    return {};
  const int a = (normal + 1) % 3, b = (normal + 2) % 3;
  std::map<std::pair<long long, long long>, std::vector<int>> cells;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int first = lin.observationOf(static_cast<int>(i));
    if (first < 0)
      continue;
    std::vector<int>& cell = cells[{static_cast<long long>(std::floor(points[i][a] / edge)),
                                    static_cast<long long>(std::floor(points[i][b] / edge))}];
    for (int j = 0; j < lin.countOf(static_cast<int>(i)); ++j)
      cell.push_back(first + j);
  }
  std::vector<std::size_t> sizes;
  for (const auto& cell : cells)
    sizes.push_back(cell.second.size());
  if (sizes.empty())
    return {};
  std::nth_element(sizes.begin(), sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2), sizes.end());
  const std::size_t min_size = std::max<std::size_t>(2, sizes[sizes.size() / 2] / 2);
  std::vector<std::vector<int>> blocks;
  for (auto& cell : cells)
    if (cell.second.size() >= min_size)
      blocks.push_back(std::move(cell.second));
  return blocks;
}

/// The h blocks of smallest mean square at X: the criterion (mean of their mean squares) and
/// their observations.
double
trimmedBlocks(const LinearizedMatching& lin, const std::vector<std::vector<int>>& blocks, std::size_t h,
              const Vector7d& X, std::vector<int>& observations)
{
  Eigen::VectorXd v;
  lin.residuals(X, v);
  std::vector<std::pair<double, std::size_t>> squares(blocks.size());
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    double sum = 0.0;
    for (int j : blocks[k])
      sum += v[j] * v[j];
    squares[k] = {sum / static_cast<double>(blocks[k].size()), k};
  }
  std::nth_element(squares.begin(), squares.begin() + static_cast<std::ptrdiff_t>(h - 1), squares.end());
  double criterion = 0.0;
  observations.clear();
  for (std::size_t k = 0; k < h; ++k) {
    criterion += squares[k].first;
    const std::vector<int>& block = blocks[squares[k].second];
    observations.insert(observations.end(), block.begin(), block.end());
  }
  return criterion / static_cast<double>(h);
}

/// A seed fit concentrated: refit on the h best blocks while the criterion falls (it never
/// rises); infinite criterion when the fit fails.
struct Trial
{
  double criterion = std::numeric_limits<double>::infinity();
  Vector7d X = identityParameters();
  std::size_t observations = 0;  // in the h best blocks
};

Trial
concentrate(const LinearizedMatching& lin, const std::vector<std::vector<int>>& blocks, std::size_t h,
            const Vector7d& X0, int max_steps)
{
  Trial t;
  t.X = X0;
  std::vector<int> chosen, next_chosen;
  t.criterion = trimmedBlocks(lin, blocks, h, t.X, chosen);
  for (int step = 0; step < max_steps; ++step) {
    Vector7d next;
    if (!lin.fit(chosen.data(), chosen.size(), next))
      break;
    const double c = trimmedBlocks(lin, blocks, h, next, next_chosen);
    if (!(c < t.criterion * (1.0 - 1e-12)))
      break;
    t.criterion = c;
    t.X = next;
    chosen.swap(next_chosen);
  }
  t.observations = chosen.size();
  return t;
}

}  // namespace

BlockTrimmedSquaresResult
blockTrimmedSquares(const LinearizedMatching& lin, const Vector7d& start,
                    const BlockTrimmedSquaresSettings& s)
{
  BlockTrimmedSquaresResult out;
  const std::vector<std::vector<int>> blocks = observationBlocks(lin, s.block_spacings);
  out.blocks = blocks.size();
  if (!(s.coverage > 0.0 && s.coverage <= 1.0))
    return out;
  const auto h = static_cast<std::size_t>(std::ceil(s.coverage * static_cast<double>(blocks.size())));
  if (h == 0 || blocks.size() < static_cast<std::size_t>(std::max(1, s.seed_blocks)))
    return out;
  out.kept = h;
  // The seeds are drawn first, in order, so that the result does not depend on the threads.
  std::mt19937 rng(s.seed);
  std::uniform_int_distribution<std::size_t> pick(0, blocks.size() - 1);
  std::vector<std::vector<std::size_t>> seeds(static_cast<std::size_t>(std::max(0, s.trials)));
  for (auto& seed : seeds)
    for (int q = 0; q < s.seed_blocks; ++q)
      seed.push_back(pick(rng));
  std::vector<Trial> trials(seeds.size() + 1);
  trials[0] = concentrate(lin, blocks, h, start, s.max_csteps);  // the given estimate
#pragma omp parallel for schedule(dynamic, 8)
  for (std::size_t t = 0; t < seeds.size(); ++t) {
    std::vector<int> observations;
    for (std::size_t b : seeds[t])
      observations.insert(observations.end(), blocks[b].begin(), blocks[b].end());
    Vector7d X;
    if (lin.fit(observations.data(), observations.size(), X))
      trials[t + 1] = concentrate(lin, blocks, h, X, s.max_csteps);
  }
  const Trial* best = nullptr;
  for (const Trial& t : trials)  // first of the smallest: deterministic
    if (std::isfinite(t.criterion) && (!best || t.criterion < best->criterion))
      best = &t;
  out.ok = best != nullptr;
  if (out.ok) {
    out.parameters = best->X;
    out.scale = std::sqrt(best->criterion);
    out.support =
        static_cast<double>(best->observations) / static_cast<double>(std::max<std::size_t>(lin.size(), 1));
  }
  return out;
}

}  // namespace pcl_ls3d
