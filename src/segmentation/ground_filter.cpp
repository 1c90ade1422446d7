/// \file ground_filter.cpp
/// \brief Grid of lowest points and the progressive morphological ground filter.

#include <pcl_ls3d/segmentation/ground_filter.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

namespace pcl_ls3d {
namespace segmentation {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

/// Sliding minimum (or maximum with \a sign −1) over [i − h, i + h] of a strided line, in
/// place, with a monotone queue: O(n) whatever h. Missing values are ±inf and never win.
void
slideLine(float* v, int n, int stride, int h, float sign, std::vector<float>& tmp)
{
  tmp.resize(static_cast<std::size_t>(n));
  std::deque<int> q;  // indices with increasing sign·value
  int next = 0;
  for (int i = 0; i < n; ++i) {
    for (; next < n && next <= i + h; ++next) {
      const float x = sign * v[next * stride];
      while (!q.empty() && sign * v[q.back() * stride] >= x)
        q.pop_back();
      q.push_back(next);
    }
    while (q.front() < i - h)
      q.pop_front();
    tmp[static_cast<std::size_t>(i)] = v[q.front() * stride];
  }
  for (int i = 0; i < n; ++i)
    v[i * stride] = tmp[static_cast<std::size_t>(i)];
}

/// Separable square min (sign 1) or max (sign −1) filter of half size h.
void
filter2D(std::vector<float>& z, int rows, int cols, int h, float sign)
{
  std::vector<float> tmp;
  for (int r = 0; r < rows; ++r)
    slideLine(z.data() + static_cast<std::size_t>(r) * cols, cols, 1, h, sign, tmp);
  for (int c = 0; c < cols; ++c)
    slideLine(z.data() + c, rows, cols, h, sign, tmp);
}

}  // namespace

LowestPointGrid::LowestPointGrid(const std::vector<Eigen::Vector3f>& points, double cell)
: cell_(cell > 0.0 ? cell : 1.0)
{
  if (points.empty())
    return;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const auto& p : points) {
    lo = lo.cwiseMin(p.head<2>().cast<double>());
    hi = hi.cwiseMax(p.head<2>().cast<double>());
  }
  min_ = lo;
  // Guard against absurd grids (a stray point km away): at most ~64 M cells.
  const double span = std::max(hi.x() - lo.x(), hi.y() - lo.y());
  cell_ = std::max(cell_, span / 8000.0);
  cols_ = static_cast<int>((hi.x() - lo.x()) / cell_) + 1;
  rows_ = static_cast<int>((hi.y() - lo.y()) / cell_) + 1;
  lowest_.assign(static_cast<std::size_t>(rows_) * cols_, std::numeric_limits<float>::quiet_NaN());
  for (const auto& p : points) {
    float& z = lowest_[static_cast<std::size_t>(cellOf(p))];
    if (!(z <= p.z()))
      z = p.z();
  }
}

int
LowestPointGrid::cellOf(const Eigen::Vector3f& p) const
{
  const int c = std::clamp(static_cast<int>((p.x() - min_.x()) / cell_), 0, cols_ - 1);
  const int r = std::clamp(static_cast<int>((p.y() - min_.y()) / cell_), 0, rows_ - 1);
  return r * cols_ + c;
}

namespace {

/// Half sizes 1, 2, 4, ... of the windows, up to the first whose width reaches max_window.
std::vector<int>
halfSizes(const LowestPointGrid& grid, double max_window)
{
  std::vector<int> halves;
  for (int half = 1;; half *= 2) {
    halves.push_back(half);
    const int window = 2 * half + 1;
    if (window * grid.cell() >= max_window || window > 2 * std::max(grid.rows(), grid.cols()))
      return halves;
  }
}

/// The grid of lowest points padded by \a pad cells on every side with the value of the nearest
/// edge cell. A window cut off at the edge of the data would otherwise erode a slope rising
/// towards the edge without the dilation restoring it; a flat continuation is preserved by
/// opening. Empty cells are +inf, so that erosion fills them from their neighbours.
std::vector<float>
paddedSurface(const LowestPointGrid& grid, int pad)
{
  const int rows = grid.rows() + 2 * pad, cols = grid.cols() + 2 * pad;
  std::vector<float> z(static_cast<std::size_t>(rows) * cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int sr = std::clamp(r - pad, 0, grid.rows() - 1);
      const int sc = std::clamp(c - pad, 0, grid.cols() - 1);
      const float v = grid.lowest()[static_cast<std::size_t>(sr) * grid.cols() + sc];
      z[static_cast<std::size_t>(r) * cols + c] = std::isnan(v) ? kInf : v;
    }
  return z;
}

}  // namespace

std::vector<char>
groundPoints(const std::vector<Eigen::Vector3f>& points, const GroundFilterSettings& s)
{
  std::vector<char> ground(points.size(), 1);
  if (points.empty())
    return ground;
  const LowestPointGrid grid(points, s.cell);
  const std::vector<int> halves = halfSizes(grid, s.max_window);
  const int pad = halves.back();
  const int rows = grid.rows() + 2 * pad, cols = grid.cols() + 2 * pad;
  std::vector<std::size_t> cell_of(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int c = grid.cellOf(points[i]);
    cell_of[i] = static_cast<std::size_t>(c / grid.cols() + pad) * cols +
                 static_cast<std::size_t>(c % grid.cols() + pad);
  }
  std::vector<float> z = paddedSurface(grid, pad);
  int previous_window = 1;
  for (const int half : halves) {
    const int window = 2 * half + 1;
    filter2D(z, rows, cols, half, 1.f);   // erosion
    for (float& v : z)
      if (v == kInf)
        v = -kInf;  // still empty: must not win the dilation
    filter2D(z, rows, cols, half, -1.f);  // dilation
    for (float& v : z)
      if (v == -kInf)
        v = kInf;
    const double dh =
        half == 1 ? s.initial_distance
                  : std::min(s.max_distance, s.initial_distance +
                                                 s.slope * (window - previous_window) * grid.cell());
    for (std::size_t i = 0; i < points.size(); ++i)
      if (ground[i] && points[i].z() - z[cell_of[i]] > dh)
        ground[i] = 0;
    previous_window = window;
  }
  return ground;
}

namespace {

/// Ground points of one grid cell: count, mean and central second moments (x, y against x, y, z).
struct CellMoments
{
  double n = 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double xx = 0.0, xy = 0.0, yy = 0.0, xz = 0.0, yz = 0.0;
};

/// Moments of the cells that hold ground points, and per grid cell its entry (−1: none). Only
/// occupied cells carry moments: a far outlier can stretch the grid to its 64 M-cell cap.
struct GroundMoments
{
  std::vector<int> entry;
  std::vector<CellMoments> cells;
};

GroundMoments
groundMoments(const std::vector<Eigen::Vector3f>& points, const std::vector<char>& ground,
              const LowestPointGrid& grid)
{
  GroundMoments g;
  g.entry.assign(static_cast<std::size_t>(grid.rows()) * static_cast<std::size_t>(grid.cols()), -1);
  const auto cellOf = [&](std::size_t i) -> CellMoments& {
    int& e = g.entry[static_cast<std::size_t>(grid.cellOf(points[i]))];
    if (e < 0) {
      e = static_cast<int>(g.cells.size());
      g.cells.emplace_back();
    }
    return g.cells[static_cast<std::size_t>(e)];
  };
  for (std::size_t i = 0; i < points.size(); ++i)
    if (ground[i]) {
      CellMoments& c = cellOf(i);
      c.n += 1.0;
      c.mean += points[i].cast<double>();
    }
  for (CellMoments& c : g.cells)
    c.mean /= c.n;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (ground[i]) {
      CellMoments& c = cellOf(i);
      const Eigen::Vector3d u = points[i].cast<double>() - c.mean;
      c.xx += u.x() * u.x();
      c.xy += u.x() * u.y();
      c.yy += u.y() * u.y();
      c.xz += u.x() * u.z();
      c.yz += u.y() * u.z();
    }
  return g;
}

}  // namespace

std::vector<float>
heightAboveTerrain(const std::vector<Eigen::Vector3f>& points, const std::vector<char>& ground,
                   const std::vector<char>& wanted, double half_width)
{
  std::vector<float> height(points.size(), std::numeric_limits<float>::quiet_NaN());
  if (points.empty() || half_width <= 0.0)
    return height;
  // Moments per cell make each query O(1): 3 x 3 cells of 2/3 half_width around the point.
  const LowestPointGrid grid(points, 2.0 * half_width / 3.0);
  const GroundMoments moments = groundMoments(points, ground, grid);
  const double cell_area = grid.cell() * grid.cell();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!wanted[i])
      continue;
    // Normal equations of z = a + b·dx + c·dy, d = offset from the point: its height is z − a.
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    const Eigen::Vector2d q = points[i].head<2>().cast<double>();
    const int c = grid.cellOf(points[i]), row = c / grid.cols(), col = c % grid.cols();
    for (int r = std::max(0, row - 1); r <= std::min(grid.rows() - 1, row + 1); ++r)
      for (int k = std::max(0, col - 1); k <= std::min(grid.cols() - 1, col + 1); ++k) {
        const int e = moments.entry[static_cast<std::size_t>(r) * static_cast<std::size_t>(grid.cols()) +
                                    static_cast<std::size_t>(k)];
        if (e < 0)
          continue;
        const CellMoments& m = moments.cells[static_cast<std::size_t>(e)];
        const Eigen::Vector2d d = m.mean.head<2>() - q;
        normal(0, 0) += m.n;
        normal(0, 1) += m.n * d.x();
        normal(0, 2) += m.n * d.y();
        normal(1, 1) += m.xx + m.n * d.x() * d.x();
        normal(1, 2) += m.xy + m.n * d.x() * d.y();
        normal(2, 2) += m.yy + m.n * d.y() * d.y();
        rhs += Eigen::Vector3d(m.n * m.mean.z(), m.xz + m.n * d.x() * m.mean.z(),
                               m.yz + m.n * d.y() * m.mean.z());
      }
    if (normal(0, 0) < 6.0)
      continue;
    normal.triangularView<Eigen::StrictlyLower>() = normal.transpose();
    const Eigen::LDLT<Eigen::Matrix3d> fit(normal);
    if (fit.info() != Eigen::Success || fit.vectorD().minCoeff() <= 1e-9 * normal(0, 0) * cell_area)
      continue;  // collinear ground points: no plane
    height[i] = static_cast<float>(static_cast<double>(points[i].z()) - fit.solve(rhs)(0));
  }
  return height;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
