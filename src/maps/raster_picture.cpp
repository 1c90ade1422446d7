#include "raster_picture.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace maps {
namespace detail {

namespace {

// The cells [c0, c1) × [r0, r1) under pixel (px, py) of a map drawn at scale < 1.
struct CellRange
{
  int c0, c1, r0, r1;
};

CellRange
cellsUnder(const GridGeometry& g, double scale, int px, int py)
{
  const int c0 = static_cast<int>(px / scale), r0 = static_cast<int>(py / scale);
  const int c1 = std::max(c0 + 1, std::min(g.cols, static_cast<int>((px + 1) / scale)));
  const int r1 = std::max(r0 + 1, std::min(g.rows, static_cast<int>((py + 1) / scale)));
  return {c0, std::min(c1, g.cols), r0, std::min(r1, g.rows)};
}

// Mean of the finite cells under pixel (px, py).
float
sampleCells(const Raster& r, double scale, int px, int py)
{
  const CellRange u = cellsUnder(r.grid, scale, px, py);
  double sum = 0.0;
  int n = 0;
  for (int y = u.r0; y < u.r1; ++y)
    for (int x = u.c0; x < u.c1; ++x)
      if (std::isfinite(r.at(x, y))) {
        sum += r.at(x, y);
        ++n;
      }
  return n ? static_cast<float>(sum / n) : std::numeric_limits<float>::quiet_NaN();
}

// 1 where a marked cell lies under pixel (px, py), else 0.
float
anyMarked(const Raster& r, double scale, int px, int py)
{
  const CellRange u = cellsUnder(r.grid, scale, px, py);
  for (int y = u.r0; y < u.r1; ++y)
    for (int x = u.c0; x < u.c1; ++x)
      if (r.at(x, y) > 0.5f)
        return 1.0f;
  return 0.0f;
}

bool
isMarked(const Raster& m, int col, int row)
{
  return col >= 0 && row >= 0 && col < m.grid.cols && row < m.grid.rows && m.at(col, row) > 0.5f;
}

// Which side of the edge between cells a (above or left) and b is marked: 0 none or both, +1 b
// (below or right), −1 a.
int
markedSide(bool a, bool b)
{
  return a == b ? 0 : b ? 1 : -1;
}

// Runs of border edges along one line of cells: `side(k)` is the k-th edge's markedSide();
// `segment(first, end, side)` receives each run of one side (first edge, one past its last).
template <typename Side, typename Segment>
void
joinRuns(int count, Side side, Segment segment)
{
  for (int k = 0; k < count;) {
    const int s = side(k);
    if (s == 0) {
      ++k;
      continue;
    }
    const int start = k;
    while (k < count && side(k) == s)
      ++k;
    segment(start, k, s);
  }
}

}  // namespace

Image
cellPixels(const Raster& raster, double scale, const ColourMap& colours, Rgb no_data)
{
  const GridGeometry& g = raster.grid;
  const bool enlarged = scale >= 1.0;
  const int factor = enlarged ? static_cast<int>(scale) : 1;
  const int w = std::max(1, static_cast<int>(g.cols * scale)),
            h = std::max(1, static_cast<int>(g.rows * scale));
  Image pixels(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float v = enlarged ? raster.at(x / factor, y / factor) : sampleCells(raster, scale, x, y);
      pixels.set(x, y, std::isfinite(v) ? colours.colour(v) : no_data);
    }
  return pixels;
}

Raster
markedPixels(const Raster& marked, double scale)
{
  GridGeometry g;
  g.cols = std::max(1, static_cast<int>(marked.grid.cols * scale));
  g.rows = std::max(1, static_cast<int>(marked.grid.rows * scale));
  Raster pixels(g);
  for (int y = 0; y < g.rows; ++y)
    for (int x = 0; x < g.cols; ++x)
      pixels.at(x, y) = anyMarked(marked, scale, x, y);
  return pixels;
}

std::vector<Eigen::Vector4d>
outlineSegments(const Raster& marked, double scale, double x0, double y0, double inset)
{
  if (scale < 1.0)  // outline the pixels that show a marked cell, as the averaged map shows them
    return outlineSegments(markedPixels(marked, scale), 1.0, x0, y0, inset);
  std::vector<Eigen::Vector4d> segments;
  const int cols = marked.grid.cols, rows = marked.grid.rows;
  for (int row = 0; row <= rows; ++row) {  // horizontal edges above each row (and below the last)
    const double y = y0 + row * scale;
    joinRuns(
        cols, [&](int c) { return markedSide(isMarked(marked, c, row - 1), isMarked(marked, c, row)); },
        [&](int a, int b, int side) {
          segments.emplace_back(x0 + a * scale, y + side * inset, x0 + b * scale, y + side * inset);
        });
  }
  for (int col = 0; col <= cols; ++col) {  // vertical edges left of each column
    const double x = x0 + col * scale;
    joinRuns(
        rows, [&](int r) { return markedSide(isMarked(marked, col - 1, r), isMarked(marked, col, r)); },
        [&](int a, int b, int side) {
          segments.emplace_back(x + side * inset, y0 + a * scale, x + side * inset, y0 + b * scale);
        });
  }
  return segments;
}

}  // namespace detail
}  // namespace maps
}  // namespace pcl_ls3d
