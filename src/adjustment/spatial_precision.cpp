#include <pcl_ls3d/adjustment/spatial_precision.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {

namespace {

constexpr int kBits = 21;
constexpr std::int64_t kMask = (std::int64_t(1) << kBits) - 1;

std::uint64_t
cellKey(std::int64_t x, std::int64_t y, std::int64_t z)
{
  return (static_cast<std::uint64_t>(x & kMask) << (2 * kBits)) |
         (static_cast<std::uint64_t>(y & kMask) << kBits) | static_cast<std::uint64_t>(z & kMask);
}

std::int64_t
signExtend(std::uint64_t v)
{
  const std::int64_t x = static_cast<std::int64_t>(v & static_cast<std::uint64_t>(kMask));
  return x >= (std::int64_t(1) << (kBits - 1)) ? x - (std::int64_t(1) << kBits) : x;
}

Eigen::Array3i
cellOf(const Eigen::Vector3d& x, double inv_cell)
{
  return (x * inv_cell).array().floor().cast<int>();
}

}  // namespace

void
SpatialScoreSum::add(const Eigen::Vector3d& x, const Vector7d& a, double p, const Vector7d& score)
{
  const Eigen::Array3i c = cellOf(x, inv_cell_);
  Cell& cell = cells_[cellKey(c.x(), c.y(), c.z())];
  cell.score += score;
  cell.normal.selfadjointView<Eigen::Upper>().rankUpdate(a, p);
}

Matrix7d
SpatialScoreSum::meat(const Matrix7d* q) const
{
  Matrix7d M = Matrix7d::Zero();
  std::unordered_map<std::uint64_t, Cell> blocks;
  blocks.reserve(cells_.size());
  for (int shift = 0; shift < 8; ++shift) {
    const int sx = shift & 1, sy = (shift >> 1) & 1, sz = (shift >> 2) & 1;
    blocks.clear();
    for (const auto& kv : cells_) {
      const std::int64_t x = signExtend(kv.first >> (2 * kBits)), y = signExtend(kv.first >> kBits),
                         z = signExtend(kv.first);
      // Block of 2 × 2 × 2 cells; floor division for negative indices.
      auto half = [](std::int64_t v) { return v >= 0 ? v / 2 : -((1 - v) / 2); };
      Cell& b = blocks[cellKey(half(x + sx), half(y + sy), half(z + sz))];
      b.score += kv.second.score;
      b.normal += kv.second.normal;
    }
    for (const auto& kv : blocks) {
      Vector7d s = kv.second.score;
      if (q) {
        const Matrix7d nb = kv.second.normal.selfadjointView<Eigen::Upper>();
        const Matrix7d I_NQ = Matrix7d::Identity() - nb * (*q);
        const Eigen::FullPivLU<Matrix7d> lu(I_NQ);
        // A block holding (nearly) all the information cannot be corrected: keep it plain.
        if (lu.isInvertible() && lu.rcond() > 1e-3)
          s = lu.solve(s);
      }
      M.noalias() += s * s.transpose();
    }
  }
  M /= 8.0;
  return 0.5 * (M + M.transpose());
}

}  // namespace pcl_ls3d
