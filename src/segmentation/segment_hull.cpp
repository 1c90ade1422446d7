/// \file segment_hull.cpp
/// \brief Convex-hull contour and volume of a segment, degenerate cases handled first; qhull
///        (libqhull_r, as in pcl::ConvexHull) runs silently.

#include <pcl_ls3d/segmentation/segment_hull.h>

#include <pcl/surface/qhull.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace pcl_ls3d {
namespace segmentation {
namespace {

/// qhull's messages go here, not to stderr: a degenerate set is an expected case that the
/// caller handles (QH6154 "initial simplex is flat" used to print ~40 lines on a real tile).
FILE*
quietSink()
{
  static FILE* sink = std::fopen("/dev/null", "w");  // thread-safe initialisation
  return sink;
}

/// Convex hull of \a coords (\a dim = 2 or 3 coordinates per point, centred) by libqhull_r
/// with option Qt, as pcl::ConvexHull runs it, but silent. Fills contour (vertex ids) and, in
/// 3-D, the volume and the outward facet planes (n·(x − centre) + offset ≤ 0 inside).
bool
runQhull(std::vector<coordT>& coords, int dim, const Eigen::Vector3d& centre, SegmentHull& out)
{
  const int n = static_cast<int>(coords.size()) / dim;
  FILE* sink = quietSink();
  qhT qh_qh;
  qhT* qh = &qh_qh;
  qh_zero(qh, sink);
  char flags[] = "qhull Qt";
  const int exitcode = qh_new_qhull(qh, dim, n, coords.data(), False, flags, nullptr, sink);
  bool ok = exitcode == 0 && qh->num_vertices > 0;
  if (ok) {
    out.contour.clear();
    vertexT* vertex;
    FORALLvertices out.contour.push_back(qh_pointid(qh, vertex->point));
    std::sort(out.contour.begin(), out.contour.end());
    out.volume = 0.0;
    out.planes.clear();
    if (dim == 3) {
      qh_getarea(qh, qh->facet_list);
      out.volume = std::abs(qh->totvol);
      facetT* facet;
      FORALLfacets
      {
        const Eigen::Vector3d nrm(facet->normal[0], facet->normal[1], facet->normal[2]);
        if (!(nrm.norm() > 0.0))
          continue;
        out.planes.emplace_back(nrm.x(), nrm.y(), nrm.z(), facet->offset - nrm.dot(centre));
      }
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  return ok && !out.contour.empty();
}

/// The mean of the points and the eigen decomposition of their covariance.
Eigen::Vector3d
principalAxes(const std::vector<Eigen::Vector3f>& points, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>& es)
{
  const std::size_t n = points.size();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points)
    mean += p.cast<double>();
  mean /= static_cast<double>(n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector3d d = p.cast<double>() - mean;
    cov.noalias() += d * d.transpose();
  }
  cov /= static_cast<double>(n);
  es.computeDirect(cov);
  return mean;
}

/// Every point is a contour point.
void
allPointsContour(std::size_t n, SegmentHull& out)
{
  out.contour.resize(n);
  std::iota(out.contour.begin(), out.contour.end(), 0);
}

/// The two extreme points along the principal axis.
void
collinearContour(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3d& mean,
                 const Eigen::Vector3d& axis, SegmentHull& out)
{
  const std::size_t n = points.size();
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i)
    t[i] = axis.dot(points[i].cast<double>() - mean);
  const auto mm = std::minmax_element(t.begin(), t.end());
  out.contour = {static_cast<int>(mm.first - t.begin()), static_cast<int>(mm.second - t.begin())};
}

/// 3-D hull of the centred points.
bool
solidHull(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3d& mean, SegmentHull& out)
{
  const std::size_t n = points.size();
  std::vector<coordT> coords(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      coords[3 * i + k] = static_cast<double>(points[i][k]) - mean[k];
  return runQhull(coords, 3, mean, out);
}

/// 2-D hull in the best-fit plane (the two largest principal directions).
bool
flatHull(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3d& mean,
         const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>& es, SegmentHull& out)
{
  const std::size_t n = points.size();
  std::vector<coordT> coords(2 * n);
  const Eigen::Vector3d u = es.eigenvectors().col(2), v = es.eigenvectors().col(1);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d d = points[i].cast<double>() - mean;
    coords[2 * i] = u.dot(d);
    coords[2 * i + 1] = v.dot(d);
  }
  return runQhull(coords, 2, mean, out);
}

}  // namespace

SegmentHull
computeSegmentHull(const std::vector<Eigen::Vector3f>& points)
{
  SegmentHull out;
  const std::size_t n = points.size();
  if (n == 0)
    return out;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  const Eigen::Vector3d mean = principalAxes(points, es);
  const Eigen::Vector3d lambda = es.eigenvalues().cwiseMax(0.0);  // ascending
  if (n < 4 || !(lambda[2] > 0.0)) {
    out.kind = HullKind::Tiny;
    allPointsContour(n, out);
    return out;
  }
  if (lambda[1] <= kHullDegeneracyTolerance * lambda[2]) {
    out.kind = HullKind::Collinear;
    collinearContour(points, mean, es.eigenvectors().col(2), out);
    return out;
  }
  const bool flat = lambda[0] <= kHullDegeneracyTolerance * lambda[2];
  if (!flat && solidHull(points, mean, out)) {
    out.kind = HullKind::Solid;
    return out;
  }
  const bool planar = flatHull(points, mean, es, out);
  out.planes.clear();
  out.volume = 0.0;
  out.kind = planar ? HullKind::Flat : HullKind::Tiny;
  if (!planar)  // qhull refused both: keep every point as contour
    allPointsContour(n, out);
  return out;
}

bool
insideHull(const SegmentHull& hull, const std::vector<Eigen::Vector3f>& points, double tol)
{
  if (hull.kind != HullKind::Solid || hull.planes.empty())
    return false;
  for (const auto& p : points) {
    const Eigen::Vector4d x(p.x(), p.y(), p.z(), 1.0);
    for (const auto& plane : hull.planes)
      if (plane.dot(x) > tol)
        return false;
  }
  return true;
}

}  // namespace segmentation
}  // namespace pcl_ls3d
