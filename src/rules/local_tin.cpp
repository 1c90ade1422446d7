#include <pcl_ls3d/rules/local_tin.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace tin {

Eigen::Matrix3d
neighbourhoodCovariance(const TargetSurface& target, const std::vector<int>& indices, int count,
                        Eigen::Vector3d& mean)
{
  mean = Eigen::Vector3d::Zero();
  for (int i = 0; i < count; ++i)
    mean += target.point(indices[static_cast<std::size_t>(i)]);
  mean /= count;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d d = target.point(indices[static_cast<std::size_t>(i)]) - mean;
    cov.noalias() += d * d.transpose();
  }
  return cov / count;
}

bool
neighbourhoodPca(const TargetSurface& target, const std::vector<int>& indices, int count,
                 Eigen::Vector3d& normal, Eigen::Vector3d& eigenvalues)
{
  if (count < 3)
    return false;
  Eigen::Vector3d mean;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(neighbourhoodCovariance(target, indices, count, mean));
  eigenvalues = es.eigenvalues();
  // Degenerate when the neighbourhood is (nearly) a line: second eigenvalue ~ 0.
  if (!(eigenvalues[1] > 1e-12 * eigenvalues[2]))
    return false;
  normal = es.eigenvectors().col(0).normalized();
  return normal.allFinite();
}

bool
planeNormal(const TargetSurface& target, const std::vector<int>& indices, int count, Eigen::Vector3d& normal)
{
  Eigen::Vector3d eigenvalues;
  return neighbourhoodPca(target, indices, count, normal, eigenvalues);
}

bool
wellSpread(const Eigen::Vector3d& eigenvalues, double min_ratio)
{
  return eigenvalues[1] >= min_ratio * eigenvalues[2];
}

bool
centredSupport(const std::vector<Eigen::Vector2d>& projected, double max_offset)
{
  if (projected.empty())
    return false;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : projected)
    mean += p;
  mean /= static_cast<double>(projected.size());
  double ms = 0.0;
  for (const auto& p : projected)
    ms += (p - mean).squaredNorm();
  ms /= static_cast<double>(projected.size());
  return mean.squaredNorm() <= max_offset * max_offset * ms;
}

namespace {

// Cross product a × b: the edge function of the edge a → b at the origin.
double
cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

bool
containsOrigin(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c)
{
  // Signs of the three edge functions at the origin must agree (either orientation).
  const double d1 = cross(a, b);
  const double d2 = cross(b, c);
  const double d3 = cross(c, a);
  const bool has_neg = d1 < 0.0 || d2 < 0.0 || d3 < 0.0;
  const bool has_pos = d1 > 0.0 || d2 > 0.0 || d3 > 0.0;
  const double area2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  return !(has_neg && has_pos) && std::abs(area2) > 1e-12 * (b - a).squaredNorm();
}

namespace {

// True when all points lie in an open half-plane through the origin with an angular margin,
// i.e. the origin is clearly outside their convex hull and no triangle of them can enclose it:
// the largest gap between the points' directions exceeds π. Queries at the border of the target
// meet this case often, and the search over all triples would try every one to learn it.
bool
clearlyOutsideHull(const std::vector<Eigen::Vector2d>& points, std::vector<double>& angles)
{
  angles.clear();
  for (const auto& p : points) {
    if (!(p.squaredNorm() > 0.0))
      return false;  // a point at the query: its triangles may enclose it
    angles.push_back(std::atan2(p.y(), p.x()));
  }
  std::sort(angles.begin(), angles.end());
  double largest_gap = angles.front() + 2.0 * M_PI - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i)
    largest_gap = std::max(largest_gap, angles[i] - angles[i - 1]);
  return largest_gap > M_PI + 1e-6;
}

// The smallest enclosing triangle with vertices from `order` (sorted by distance r) and, when
// fixed >= 0, through point `fixed`; visiting in order of distance lets the search stop once no
// smaller triangle can follow (the sums only grow). `best` and `triangle` carry the best so far.
void
smallestEnclosing(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& r,
                  const std::vector<int>& order, int fixed, double& best, std::array<int, 3>& triangle)
{
  const std::size_t m = order.size();
  auto at = [&](std::size_t i) { return static_cast<std::size_t>(order[i]); };
  auto tryTriangle = [&](int a, int b, int c, double size) {
    if (size < best &&
        containsOrigin(points[static_cast<std::size_t>(a)], points[static_cast<std::size_t>(b)],
                       points[static_cast<std::size_t>(c)])) {
      best = size;
      triangle = {a, b, c};
      std::sort(triangle.begin(), triangle.end());
    }
  };
  if (fixed >= 0) {
    // The origin can lie in (fixed, j, k) only when j and k are not strictly on the same side of
    // the line through the origin and `fixed` (containsOrigin's first and third edge functions).
    const Eigen::Vector2d& f = points[static_cast<std::size_t>(fixed)];
    const double r0 = r[static_cast<std::size_t>(fixed)];
    thread_local std::vector<double> sides;
    sides.resize(m);
    double* side = sides.data();  // one thread-local lookup, not one per pair
    for (std::size_t i = 0; i < m; ++i)
      side[i] = cross(f, points[at(i)]);
    for (std::size_t j = 0; j + 1 < m && r0 + r[at(j)] + r[at(j + 1)] < best; ++j)
      for (std::size_t k = j + 1; k < m && r0 + r[at(j)] + r[at(k)] < best; ++k)
        if (!(side[j] > 0.0 && side[k] > 0.0) && !(side[j] < 0.0 && side[k] < 0.0))
          tryTriangle(fixed, order[j], order[k], r0 + r[at(j)] + r[at(k)]);
    return;
  }
  for (std::size_t i = 0; i + 2 < m && r[at(i)] + r[at(i + 1)] + r[at(i + 2)] < best; ++i)
    for (std::size_t j = i + 1; j + 1 < m && r[at(i)] + r[at(j)] + r[at(j + 1)] < best; ++j)
      for (std::size_t k = j + 1; k < m && r[at(i)] + r[at(j)] + r[at(k)] < best; ++k)
        tryTriangle(order[i], order[j], order[k], r[at(i)] + r[at(j)] + r[at(k)]);
}

}  // namespace

bool
enclosingTriangle(const std::vector<Eigen::Vector2d>& points, std::array<int, 3>& triangle)
{
  const int n = static_cast<int>(points.size());
  if (n < 3)
    return false;
  // Per-thread scratch: this runs once per correspondence search, millions of times a match.
  thread_local std::vector<double> r, angles;
  thread_local std::vector<int> others;
  // Distances to the query and the other points (not the nearest) nearest first.
  r.resize(points.size());
  others.clear();
  for (int i = 0; i < n; ++i) {
    r[static_cast<std::size_t>(i)] = points[static_cast<std::size_t>(i)].norm();
    if (i > 0)
      others.push_back(i);
  }
  std::sort(others.begin(), others.end(),
            [&](int a, int b) { return r[static_cast<std::size_t>(a)] < r[static_cast<std::size_t>(b)]; });
  double best = std::numeric_limits<double>::max();
  // First triangles through the nearest point; then all triangles of the others.
  smallestEnclosing(points, r, others, 0, best, triangle);
  if (best == std::numeric_limits<double>::max() && !clearlyOutsideHull(points, angles))
    smallestEnclosing(points, r, others, -1, best, triangle);
  return best < std::numeric_limits<double>::max();
}

void
planeBasis(const Eigen::Vector3d& normal, Eigen::Vector3d& e1, Eigen::Vector3d& e2)
{
  const Eigen::Vector3d helper =
      std::abs(normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  e1 = normal.cross(helper).normalized();
  e2 = normal.cross(e1);
}

bool
quadricPatch(const TargetSurface& target, const std::vector<int>& indices, int count,
             const Eigen::Vector3d& query, const Eigen::Vector3d& normal, double& height,
             Eigen::Vector2d& slope, double* height_variance, double* residual_variance,
             Eigen::Vector2d* slope_variance)
{
  if (count < 8)
    return false;
  Eigen::Vector3d e1, e2;
  planeBasis(normal, e1, e2);
  // Normal equations of the 6-term quadric, coordinates scaled by the neighbourhood radius.
  double r2 = 0.0;
  for (int i = 0; i < count; ++i)
    r2 = std::max(r2, (target.point(indices[static_cast<std::size_t>(i)]) - query).squaredNorm());
  const double s = r2 > 0.0 ? 1.0 / std::sqrt(r2) : 1.0;
  Eigen::Matrix<double, 6, 6> N = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
  double ww = 0.0;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d d = target.point(indices[static_cast<std::size_t>(i)]) - query;
    const double u = d.dot(e1) * s, v = d.dot(e2) * s, w = d.dot(normal);
    Eigen::Matrix<double, 6, 1> a;
    a << 1, u, v, u * u, u * v, v * v;
    N.noalias() += a * a.transpose();
    b.noalias() += a * w;
    ww += w * w;
  }
  Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(N);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-9 * ldlt.vectorD().maxCoeff()))
    return false;
  const Eigen::Matrix<double, 6, 1> x = ldlt.solve(b);
  if (!x.allFinite())
    return false;
  if (height_variance)
    *height_variance = ldlt.solve(Eigen::Matrix<double, 6, 1>::Unit(0))[0];
  const double noise = std::max(0.0, ww - x.dot(b)) / (count - 6);
  if (residual_variance)
    *residual_variance = noise;
  if (slope_variance)
    *slope_variance = noise * s * s *
                      Eigen::Vector2d(ldlt.solve(Eigen::Matrix<double, 6, 1>::Unit(1))[1],
                                      ldlt.solve(Eigen::Matrix<double, 6, 1>::Unit(2))[2]);
  height = x[0];
  slope = Eigen::Vector2d(x[1] * s, x[2] * s);
  return true;
}

void
projectToPlane(const TargetSurface& target, const std::vector<int>& indices, int count,
               const Eigen::Vector3d& query, const Eigen::Vector3d& normal,
               std::vector<Eigen::Vector2d>& projected)
{
  Eigen::Vector3d e1, e2;
  planeBasis(normal, e1, e2);
  projected.resize(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d d = target.point(indices[static_cast<std::size_t>(i)]) - query;
    projected[static_cast<std::size_t>(i)] = Eigen::Vector2d(d.dot(e1), d.dot(e2));
  }
}

}  // namespace tin
}  // namespace pcl_ls3d
