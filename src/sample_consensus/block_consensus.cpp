#include <pcl_ls3d/sample_consensus/block_consensus.h>
#include <pcl_ls3d/common/voxel_index.h>

#include <cmath>
#include <map>
#include <random>
#include <utility>

namespace pcl_ls3d {

namespace {

/// Observations of `lin` by square blocks of the epoch's dominant plane.
std::vector<std::vector<int>>
observationBlocks(const LinearizedMatching& lin, const BlockConsensusSettings& s)
{
  const std::vector<Eigen::Vector3d>& points = lin.reducedPoints();
  const CloudSpacing sp = cloudSpacing(points);
  const double edge = s.block_spacings * sp.spacing;
  if (!(edge > 0.0))
    return {};
  const int a = (sp.normal_axis + 1) % 3, b = (sp.normal_axis + 2) % 3;
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
  std::vector<std::vector<int>> blocks;
  for (auto& cell : cells)
    if (cell.second.size() >= s.min_block_points)
      blocks.push_back(std::move(cell.second));
  return blocks;
}

/// The consensus of one estimate: observations of its consistent blocks and their sum of squares.
struct Consensus
{
  std::vector<int> observations;
  std::size_t blocks = 0;
  double sum_of_squares = 0.0;
};

Consensus
consensusOf(const LinearizedMatching& lin, const std::vector<std::vector<int>>& blocks, const Vector7d& X,
            double noise, double z)
{
  Eigen::VectorXd v;
  lin.residuals(X, v);
  Consensus c;
  for (const std::vector<int>& block : blocks) {
    double squares = 0.0;
    for (int j : block)
      squares += v[j] * v[j];
    const auto k = static_cast<double>(block.size());
    if (squares / k < noise * noise * (1.0 + z * std::sqrt(2.0 / k))) {
      c.observations.insert(c.observations.end(), block.begin(), block.end());
      c.sum_of_squares += squares;
      ++c.blocks;
    }
  }
  return c;
}

bool
better(const Consensus& a, const Consensus& b)
{
  return a.observations.size() > b.observations.size() ||
         (a.observations.size() == b.observations.size() && a.sum_of_squares < b.sum_of_squares);
}

}  // namespace

BlockConsensusResult
blockConsensus(const LinearizedMatching& lin, double noise, const Vector7d& start, const BlockConsensusSettings& s)
{
  BlockConsensusResult out;
  const std::vector<std::vector<int>> blocks = observationBlocks(lin, s);
  out.blocks = blocks.size();
  if (!(noise > 0.0) || blocks.size() < static_cast<std::size_t>(std::max(1, s.seed_blocks)))
    return out;
  std::mt19937 rng(s.seed);
  std::uniform_int_distribution<std::size_t> pick(0, blocks.size() - 1);
  Consensus best;
  std::vector<int> seed;
  for (int trial = 0; trial <= s.trials; ++trial) {
    Vector7d X = start;  // trial 0: the given estimate
    if (trial > 0) {
      seed.clear();
      for (int q = 0; q < s.seed_blocks; ++q) {
        const std::vector<int>& block = blocks[pick(rng)];
        seed.insert(seed.end(), block.begin(), block.end());
      }
      if (!lin.fit(seed.data(), seed.size(), X))
        continue;
    }
    // Concentration: refit on the consistent blocks until they repeat.
    Consensus c = consensusOf(lin, blocks, X, noise, s.quantile_z);
    for (int step = 0; step < s.max_steps && !c.observations.empty(); ++step) {
      Vector7d next;
      if (!lin.fit(c.observations.data(), c.observations.size(), next))
        break;
      Consensus d = consensusOf(lin, blocks, next, noise, s.quantile_z);
      const bool same = d.observations == c.observations;
      X = next;
      c = std::move(d);
      if (same)
        break;
    }
    if (!out.ok || better(c, best)) {
      out.ok = true;
      out.parameters = X;
      best = std::move(c);
    }
  }
  out.support = lin.size() > 0 ? static_cast<double>(best.observations.size()) / static_cast<double>(lin.size()) : 0.0;
  out.consistent = best.blocks;
  return out;
}

}  // namespace pcl_ls3d
