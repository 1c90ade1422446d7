#include <pcl_ls3d/strips/block_precision.h>

#include <pcl_ls3d/adjustment/spatial_precision.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace pcl_ls3d {
namespace strips {

namespace {

// One overlap's share of one cell.
struct Entry
{
  const PrecisionCell* cell;
  int i, j;
};

// Floor division for negative cell indices.
int
half(int v)
{
  return v >= 0 ? v / 2 : -((1 - v) / 2);
}

// The strips of a 2 × 2 × 2 block, its score S_T and normal matrix N_TT (7|T| each).
struct BlockSums
{
  std::vector<int> strips;
  Eigen::VectorXd score;
  Eigen::MatrixXd normal;
};

// A cell's score S = Σ p v a, or for residuals v + a·step the score S + N_c [step_i; step_j].
Vector14d
cellScore(const Entry& e, const Eigen::VectorXd* step)
{
  if (!step)
    return e.cell->score;
  Vector14d dx;
  dx << step->segment<7>(7 * e.i), step->segment<7>(7 * e.j);
  return e.cell->score + e.cell->normal * dx;
}

BlockSums
sumBlock(const std::vector<const Entry*>& entries, const Eigen::VectorXd* step)
{
  BlockSums b;
  for (const Entry* e : entries)
    for (int s : {e->i, e->j})
      if (std::find(b.strips.begin(), b.strips.end(), s) == b.strips.end())
        b.strips.push_back(s);
  std::sort(b.strips.begin(), b.strips.end());
  const Eigen::Index d = 7 * static_cast<Eigen::Index>(b.strips.size());
  b.score = Eigen::VectorXd::Zero(d);
  b.normal = Eigen::MatrixXd::Zero(d, d);
  auto slot = [&](int strip) {
    return 7 * static_cast<Eigen::Index>(std::lower_bound(b.strips.begin(), b.strips.end(), strip) -
                                         b.strips.begin());
  };
  for (const Entry* e : entries) {
    const Eigen::Index at[2] = {slot(e->i), slot(e->j)};
    const Vector14d score = cellScore(*e, step);
    for (int u = 0; u < 2; ++u) {
      b.score.segment<7>(at[u]) += score.segment<7>(7 * u);
      for (int v = 0; v < 2; ++v)
        b.normal.block<7, 7>(at[u], at[v]) += e->cell->normal.block<7, 7>(7 * u, 7 * v);
    }
  }
  return b;
}

}  // namespace

Eigen::MatrixXd
blockMiddleTerm(const std::vector<OverlapContribution>& contributions, const Eigen::MatrixXd& qxx,
                double sigma0, const Eigen::VectorXd& apriori_weights, const std::vector<bool>& determinable,
                const Eigen::VectorXd* step)
{
  const Eigen::Index u = qxx.rows();
  std::vector<Entry> entries;
  for (const OverlapContribution& c : contributions)
    for (const PrecisionCell& pc : c.cells)
      entries.push_back({&pc, c.i, c.j});
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(u, u);
  for (int shift = 0; shift < 8; ++shift) {
    const int sx = shift & 1, sy = (shift >> 1) & 1, sz = (shift >> 2) & 1;
    std::map<std::tuple<int, int, int>, std::vector<const Entry*>> blocks;
    for (const Entry& e : entries)
      blocks[{half(e.cell->x + sx), half(e.cell->y + sy), half(e.cell->z + sz)}].push_back(&e);
    for (const auto& kv : blocks) {
      BlockSums b = sumBlock(kv.second, step);
      const Eigen::Index d = b.score.size();
      Eigen::MatrixXd q(d, d);
      for (std::size_t a = 0; a < b.strips.size(); ++a)
        for (std::size_t c = 0; c < b.strips.size(); ++c)
          q.block<7, 7>(7 * static_cast<Eigen::Index>(a), 7 * static_cast<Eigen::Index>(c)) =
              qxx.block<7, 7>(7 * b.strips[a], 7 * b.strips[c]);
      // CR3: S* = (I − N_B Q)⁻¹ S, unless the block holds nearly all the information.
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(Eigen::MatrixXd::Identity(d, d) - b.normal * q);
      Eigen::VectorXd s = b.score;
      if (lu.isInvertible() && lu.rcond() > 1e-3)
        s = lu.solve(b.score);
      for (std::size_t a = 0; a < b.strips.size(); ++a)
        for (std::size_t c = 0; c < b.strips.size(); ++c)
          M.block<7, 7>(7 * b.strips[a], 7 * b.strips[c]) +=
              s.segment<7>(7 * static_cast<Eigen::Index>(a)) *
              s.segment<7>(7 * static_cast<Eigen::Index>(c)).transpose();
    }
  }
  M /= 8.0;
  M = 0.5 * (M + M.transpose()).eval();
  for (Eigen::Index p = 0; p < u; ++p)
    if (determinable[static_cast<std::size_t>(p)] && apriori_weights[p] > 0.0 &&
        std::isfinite(apriori_weights[p]))
      M(p, p) += sigma0 * sigma0 * apriori_weights[p];
  return M;
}

Eigen::MatrixXd
blockSandwichCovariance(const std::vector<OverlapContribution>& contributions, const Eigen::MatrixXd& qxx,
                        double sigma0, const Eigen::VectorXd& apriori_weights,
                        const std::vector<bool>& determinable)
{
  const Eigen::MatrixXd M = blockMiddleTerm(contributions, qxx, sigma0, apriori_weights, determinable);
  return notBelowFormal<Eigen::MatrixXd>(qxx * M * qxx, sigma0 * sigma0 * qxx);
}

}  // namespace strips
}  // namespace pcl_ls3d
