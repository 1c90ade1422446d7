/// \file ground_filter.cpp
/// \brief Grid of lowest points and the progressive morphological ground filter.

#include <pcl_ls3d/segmentation/ground_filter.h>

#include <pcl_ls3d/common/voxel_index.h>

#include "terrain_cells.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <unordered_map>

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
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const auto& p : points)
    if (p.allFinite()) {
      lo = lo.cwiseMin(p.head<2>().cast<double>());
      hi = hi.cwiseMax(p.head<2>().cast<double>());
    }
  if (!lo.allFinite())
    return;  // no finite point: an empty grid
  min_ = lo;
  // Guard against absurd grids (a stray point km away): at most ~64 M cells.
  const double span = std::max(hi.x() - lo.x(), hi.y() - lo.y());
  cell_ = std::max(cell_, span / 8000.0);
  cols_ = static_cast<int>((hi.x() - lo.x()) / cell_) + 1;
  rows_ = static_cast<int>((hi.y() - lo.y()) / cell_) + 1;
  lowest_.assign(static_cast<std::size_t>(rows_) * cols_, std::numeric_limits<float>::quiet_NaN());
  lowest_point_.assign(lowest_.size(), -1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      continue;
    const auto cell_index = static_cast<std::size_t>(cellOf(points[i]));
    float& z = lowest_[cell_index];
    if (!(z <= points[i].z())) {
      z = points[i].z();
      lowest_point_[cell_index] = static_cast<int>(i);
    }
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

/// The smaller of two differences of the same sign, 0 if their signs differ (the minmod
/// limiter): equal on a plane, 0 at a step or a ridge.
float
minmod(float a, float b)
{
  if (a * b <= 0.f)
    return 0.f;
  return std::abs(a) < std::abs(b) ? a : b;
}

/// Slope per cell along one axis of the opened surface \a z (padded by \a pad, \a stride the
/// axis step in the padded grid, \a along the cell's position along that axis, \a length the
/// real grid's length along it). Only occupied real cells count; where a neighbour is missing,
/// the two differences on the other side stand in. In height per cell.
float
axisSlope(const std::vector<float>& z, const std::vector<char>& occupied, std::size_t at,
          std::ptrdiff_t stride, int along, int length)
{
  const auto usable = [&](int k) {
    return k >= 0 && k < length && occupied[static_cast<std::size_t>(at + (k - along) * stride)];
  };
  const auto difference = [&](int k) {  // z(k + 1) − z(k), or NaN
    if (!usable(k) || !usable(k + 1))
      return std::numeric_limits<float>::quiet_NaN();
    return z[static_cast<std::size_t>(at + (k + 1 - along) * stride)] -
           z[static_cast<std::size_t>(at + (k - along) * stride)];
  };
  const float before = difference(along - 1), after = difference(along);
  if (!std::isnan(before) && !std::isnan(after))
    return minmod(before, after);
  const float outer = std::isnan(before) ? difference(along + 1) : difference(along - 2);
  const float inner = std::isnan(before) ? after : before;
  return std::isnan(inner) || std::isnan(outer) ? 0.f : minmod(inner, outer);
}

/// Slopes (x, y) of the padded opened surface at the \a cells that hold points, in height per
/// cell.
std::vector<Eigen::Vector2f>
surfaceSlopes(const std::vector<float>& z, const std::vector<char>& occupied,
              const std::vector<std::size_t>& cells, const LowestPointGrid& grid, int pad)
{
  const std::size_t cols = static_cast<std::size_t>(grid.cols() + 2 * pad);
  std::vector<Eigen::Vector2f> slope(cells.size());
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const std::size_t at = cells[k];
    const int r = static_cast<int>(at / cols) - pad, c = static_cast<int>(at % cols) - pad;
    slope[k] = Eigen::Vector2f(axisSlope(z, occupied, at, 1, c, grid.cols()),
                               axisSlope(z, occupied, at, static_cast<std::ptrdiff_t>(cols), r, grid.rows()));
  }
  return slope;
}

}  // namespace

std::vector<char>
groundPoints(const std::vector<Eigen::Vector3f>& points, const GroundFilterSettings& s)
{
  std::vector<char> ground(points.size(), 0);
  const LowestPointGrid grid(points, s.cell);
  if (grid.rows() == 0)
    return ground;  // no finite point
  const std::vector<int> halves = halfSizes(grid, s.max_window);
  const int pad = halves.back();
  const int rows = grid.rows() + 2 * pad, cols = grid.cols() + 2 * pad;
  // Per finite point: its padded cell (a slot among the occupied ones) and its offset from the
  // cell's lowest point, in cells, where the cell's opened surface is anchored.
  std::vector<std::size_t> cell_of(points.size());
  std::vector<Eigen::Vector2f> offset(points.size(), Eigen::Vector2f::Zero());
  std::vector<char> occupied(static_cast<std::size_t>(rows) * cols, 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      continue;
    ground[i] = 1;
    const int c = grid.cellOf(points[i]);
    cell_of[i] = static_cast<std::size_t>(c / grid.cols() + pad) * cols +
                 static_cast<std::size_t>(c % grid.cols() + pad);
    occupied[cell_of[i]] = 1;
    const Eigen::Vector3f& lowest = points[static_cast<std::size_t>(grid.lowestPoint()[c])];
    offset[i] = (points[i].head<2>() - lowest.head<2>()) / static_cast<float>(grid.cell());
  }
  std::vector<std::size_t> cells;
  for (std::size_t at = 0; at < occupied.size(); ++at)
    if (occupied[at])
      cells.push_back(at);
  std::vector<std::uint32_t> slot(points.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i)
    if (ground[i])
      slot[i] = static_cast<std::uint32_t>(std::lower_bound(cells.begin(), cells.end(), cell_of[i]) -
                                           cells.begin());
  std::vector<float> z = paddedSurface(grid, pad);
  int previous_window = 1;
  for (const int half : halves) {
    const int window = 2 * half + 1;
    filter2D(z, rows, cols, half, 1.f);  // erosion
    for (float& v : z)
      if (v == kInf)
        v = -kInf;                        // still empty: must not win the dilation
    filter2D(z, rows, cols, half, -1.f);  // dilation
    for (float& v : z)
      if (v == -kInf)
        v = kInf;
    const double dh = half == 1
                          ? s.initial_distance
                          : std::min(s.max_distance,
                                     s.initial_distance + s.slope * (window - previous_window) * grid.cell());
    const std::vector<Eigen::Vector2f> slope = surfaceSlopes(z, occupied, cells, grid, pad);
    for (std::size_t i = 0; i < points.size(); ++i)
      if (ground[i] && points[i].z() - z[cell_of[i]] - slope[slot[i]].dot(offset[i]) > dh)
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

/// Cells keyed by planCellKey (voxel_index.h): no cell count cap, so a far outlier neither
/// enlarges the window nor costs memory (only occupied cells are stored).
using GroundMoments = std::unordered_map<std::uint64_t, CellMoments>;

/// Column or row of a coordinate already in cells.
std::int64_t
cellIndex(double v)
{
  return planCellCoordinate(v, 1.0);
}

/// Moments of the ground points per occupied cell; coordinates in cells about \a origin.
GroundMoments
groundMoments(const std::vector<Eigen::Vector3f>& points, const std::vector<char>& ground,
              const Eigen::Vector2d& origin, double cell)
{
  GroundMoments moments;
  const auto at = [&](std::size_t i) {
    const Eigen::Vector2d c = (points[i].head<2>().cast<double>() - origin) / cell;
    return Eigen::Vector3d(c.x(), c.y(), points[i].z());
  };
  const auto keyOf = [](const Eigen::Vector3d& c) { return planCellKey(cellIndex(c.x()), cellIndex(c.y())); };
  for (std::size_t i = 0; i < points.size(); ++i)
    if (ground[i] && points[i].allFinite()) {
      const Eigen::Vector3d c = at(i);
      CellMoments& m = moments[keyOf(c)];
      m.n += 1.0;
      m.mean += c;
    }
  for (auto& [key, m] : moments)
    m.mean /= m.n;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (ground[i] && points[i].allFinite()) {
      const Eigen::Vector3d c = at(i);
      CellMoments& m = moments[keyOf(c)];
      const Eigen::Vector3d u = c - m.mean;
      m.xx += u.x() * u.x();
      m.xy += u.x() * u.y();
      m.yy += u.y() * u.y();
      m.xz += u.x() * u.z();
      m.yz += u.y() * u.z();
    }
  return moments;
}

}  // namespace

std::vector<float>
heightAboveTerrain(const std::vector<Eigen::Vector3f>& points, const std::vector<char>& ground,
                   const std::vector<char>& wanted, double half_width)
{
  std::vector<float> height(points.size(), std::numeric_limits<float>::quiet_NaN());
  if (points.empty() || !(half_width > 0.0) || ground.size() != points.size() ||
      wanted.size() != points.size())
    return height;
  // Moments per cell make each query O(1): the 3 x 3 cells of 2/3 half_width around the point.
  // Lengths in cells keep the normal equations unit-free.
  const double cell = 2.0 * half_width / 3.0;
  // Cells from the lowest x and y, as the filter's grid (LowestPointGrid) lays them.
  Eigen::Vector2d origin = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  for (const Eigen::Vector3f& p : points)
    if (p.allFinite())
      origin = origin.cwiseMin(p.head<2>().cast<double>());
  if (!origin.allFinite())
    return height;
  const GroundMoments moments = groundMoments(points, ground, origin, cell);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!wanted[i] || !points[i].allFinite())
      continue;
    // Normal equations of z = a + b·dx + c·dy, d = offset from the point: its height is z − a.
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    const Eigen::Vector2d q = (points[i].head<2>().cast<double>() - origin) / cell;
    const std::int64_t col = cellIndex(q.x()), row = cellIndex(q.y());
    for (std::int64_t r = row - 1; r <= row + 1; ++r)
      for (std::int64_t k = col - 1; k <= col + 1; ++k) {
        const auto found = moments.find(planCellKey(k, r));
        if (found == moments.end())
          continue;
        const CellMoments& m = found->second;
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
    // Ground points on a line or a strip narrower than about a third of a cell leave the slope
    // across it to chance: no plane (their spread's smaller axis below 0.1 cell).
    if (!detail::spreadsAcross(normal, 0.01))
      continue;
    normal.triangularView<Eigen::StrictlyLower>() = normal.transpose();
    height[i] = static_cast<float>(static_cast<double>(points[i].z()) - normal.ldlt().solve(rhs)(0));
  }
  return height;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
