/// \file segment_hull.cpp
/// \brief Convex-hull contour and volume of a segment, degenerate cases handled first.

#include <pcl_ls3d/segmentation/segment_hull.h>

#include <pcl/point_types.h>
#include <pcl/surface/convex_hull.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pcl_ls3d {
namespace segmentation {
namespace {

/// Volume of a closed convex triangulated hull: sum of tetrahedra from its centroid.
double
hullVolume(const pcl::PointCloud<pcl::PointXYZ>& hull,
           const std::vector<pcl::Vertices>& polygons)
{
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : hull.points)
    c += p.getVector3fMap().cast<double>();
  c /= static_cast<double>(std::max<std::size_t>(1, hull.size()));
  double v = 0.0;
  for (const auto& poly : polygons) {
    if (poly.vertices.size() < 3)
      continue;
    const Eigen::Vector3d a = hull[poly.vertices[0]].getVector3fMap().cast<double>() - c;
    for (std::size_t t = 1; t + 1 < poly.vertices.size(); ++t) {
      const Eigen::Vector3d b = hull[poly.vertices[t]].getVector3fMap().cast<double>() - c;
      const Eigen::Vector3d d = hull[poly.vertices[t + 1]].getVector3fMap().cast<double>() - c;
      v += std::abs(a.dot(b.cross(d))) / 6.0;
    }
  }
  return v;
}

/// Outward facet planes of a closed convex triangulated hull.
std::vector<Eigen::Vector4d>
hullPlanes(const pcl::PointCloud<pcl::PointXYZ>& hull, const std::vector<pcl::Vertices>& polygons)
{
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : hull.points)
    c += p.getVector3fMap().cast<double>();
  c /= static_cast<double>(std::max<std::size_t>(1, hull.size()));
  std::vector<Eigen::Vector4d> planes;
  planes.reserve(polygons.size());
  for (const auto& poly : polygons) {
    if (poly.vertices.size() < 3)
      continue;
    const Eigen::Vector3d a = hull[poly.vertices[0]].getVector3fMap().cast<double>();
    const Eigen::Vector3d b = hull[poly.vertices[1]].getVector3fMap().cast<double>();
    const Eigen::Vector3d d = hull[poly.vertices[2]].getVector3fMap().cast<double>();
    Eigen::Vector3d n = (b - a).cross(d - a);
    if (!(n.norm() > 0.0))
      continue;
    n.normalize();
    if (n.dot(c - a) > 0.0)
      n = -n;  // outward: the centroid is on the inner side
    planes.emplace_back(n.x(), n.y(), n.z(), -n.dot(a));
  }
  return planes;
}

/// Run pcl::ConvexHull in \a dim dimensions; false if qhull produced nothing.
bool
runQhull(const pcl::PointCloud<pcl::PointXYZ>::Ptr& cloud, int dim, SegmentHull& out)
{
  pcl::ConvexHull<pcl::PointXYZ> hull;
  hull.setInputCloud(cloud);
  hull.setDimension(dim);
  pcl::PointCloud<pcl::PointXYZ> vertices;
  std::vector<pcl::Vertices> polygons;
  hull.reconstruct(vertices, polygons);
  pcl::PointIndices idx;
  hull.getHullPointIndices(idx);
  if (vertices.empty() || idx.indices.empty())
    return false;
  out.contour.assign(idx.indices.begin(), idx.indices.end());
  out.volume = (dim == 3) ? hullVolume(vertices, polygons) : 0.0;
  if (dim == 3)
    out.planes = hullPlanes(vertices, polygons);
  return true;
}

}  // namespace

SegmentHull
computeSegmentHull(const std::vector<Eigen::Vector3f>& points)
{
  SegmentHull out;
  const std::size_t n = points.size();
  if (n == 0)
    return out;
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
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(cov);
  const Eigen::Vector3d lambda = es.eigenvalues().cwiseMax(0.0);  // ascending

  const auto all_points = [&]() {
    out.contour.resize(n);
    std::iota(out.contour.begin(), out.contour.end(), 0);
  };
  if (n < 4 || !(lambda[2] > 0.0)) {
    out.kind = HullKind::Tiny;
    all_points();
    return out;
  }
  if (lambda[1] <= kHullDegeneracyTolerance * lambda[2]) {
    out.kind = HullKind::Collinear;
    const Eigen::Vector3d axis = es.eigenvectors().col(2);
    std::vector<double> t(n);
    for (std::size_t i = 0; i < n; ++i)
      t[i] = axis.dot(points[i].cast<double>() - mean);
    const auto mm = std::minmax_element(t.begin(), t.end());
    out.contour = {static_cast<int>(mm.first - t.begin()), static_cast<int>(mm.second - t.begin())};
    return out;
  }
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(n);
  for (std::size_t i = 0; i < n; ++i)
    (*cloud)[i].getVector3fMap() = points[i];
  const bool flat = lambda[0] <= kHullDegeneracyTolerance * lambda[2];
  if (!flat && runQhull(cloud, 3, out)) {
    out.kind = HullKind::Solid;
    return out;
  }
  if (runQhull(cloud, 2, out)) {
    out.planes.clear();
    out.kind = HullKind::Flat;
    out.volume = 0.0;
    return out;
  }
  out.planes.clear();
  out.kind = HullKind::Tiny;  // qhull refused both: keep every point as contour
  out.volume = 0.0;
  all_points();
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
