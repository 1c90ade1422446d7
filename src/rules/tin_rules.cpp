// LND and LZD rules: both find a local TIN triangle of the target, then intersect it along the
// triangle normal (LND) or the vertical (LZD).
#include <pcl_ls3d/rules/lnd_rule.h>
#include <pcl_ls3d/rules/local_tin.h>
#include <pcl_ls3d/rules/lzd_rule.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {

namespace {

struct Scratch
{
  std::vector<int> indices;
  std::vector<float> sq_dists;
  std::vector<Eigen::Vector2d> projected;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // PCA normal of `indices`
};

// Neighbourhood quality (see tin::wellSpread / tin::centredSupport). A set of k nearest points
// that is nearly a line is widened once to kWiden·k points before the query is given up.
constexpr double kMinSpreadRatio = 0.1;  // λ1/λ2: ≤ ~3.2 : 1 anisotropy of the 2-D spread
constexpr int kWiden = 3;
// The query may sit off its neighbours' centroid by at most this × their RMS spread: interior
// points of random 20-NN sets reach 0.3–0.5 (a limit of 0.25 dropped a third of them), a point
// on the border of the target (neighbours in a half disc) ≈ 0.75.
constexpr double kMaxCentroidOffset = 0.7;
// A local quadric is used only when its height at the query is at most 0.7 times as noisy (in
// variance) as a single point (variance factor q_aa; well-spread 12-point sets give ≈ 0.35,
// 20-point sets ≈ 0.2). Zig-zag scans put most 12-NN sets on two scan lines (median q_aa 1.6 on
// generated strips; 20-NN 0.76): the fit is then redone on kWiden·k neighbours (36-NN: median
// 0.11), and the point is dropped if that fails too.
constexpr double kMaxHeightVariance = 0.7;

// Within this fraction of the neighbourhood radius of a target sample (about an eighth of the
// point spacing) the local surface is drawn towards that sample; see towardsNearestSample().
constexpr double kSnapFraction = 0.05;
// LZD supports a query within the snap radius of a sample also on the target's border (heights
// of a DEM's edge nodes are measured, not extrapolated): 7 % of a 50 × 50 grid, all its border,
// had no height difference, which made a central patch of 46 % of the nodes half of the observed
// surface. LND keeps the stricter rule its registration figures were measured with.
constexpr bool kLzdOnSample = true;

// LZD re-centres its neighbour search at the height found when that moves the centre by more
// than this fraction of the neighbourhood radius (see LzdRule::findConjugate).
constexpr double kRecentreFraction = 0.25;
constexpr int kMaxRecentring = 4;  // searches per LZD query at most (the first and 3 re-centred)

Scratch&
scratch()
{
  thread_local Scratch s;
  return s;
}

// The fitted local surface smooths the samples; at a sample itself the measurement is the best
// evidence of the surface. Near the query's nearest sample the element's point is therefore
// drawn towards that sample, linearly from nothing at the snap radius to the sample itself when
// they coincide. A cloud matched to itself or to an exact copy then has zero residuals at the
// exact answer (the fitted quadric's misfit at each sample would otherwise pull it off by up to
// ~2 σ), while on independent scans only the few per cent of queries that fall that close to a
// sample get a little of its noise. Continuous in the query, so the iteration sees one surface.
Eigen::Vector3d
towardsNearestSample(const Eigen::Vector3d& query, const TargetSurface& target,
                     const CorrespondenceCache& cache, const Eigen::Vector3d& element_point)
{
  if (cache.nearest_sample < 0 || !(cache.snap_radius > 0.f))
    return element_point;
  const Eigen::Vector3d sample = target.point(cache.nearest_sample);
  const double weight = 1.0 - (sample - query).norm() / static_cast<double>(cache.snap_radius);
  return weight > 0.0 ? Eigen::Vector3d(element_point + weight * (sample - element_point)) : element_point;
}

// Barycentric test of p's projection along `dir` onto triangle (a, b, c).
bool
projectsInto(const Eigen::Vector3d& p, const Eigen::Vector3d& dir, const Eigen::Vector3d& a,
             const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
  // Project along dir: work in the plane orthogonal to dir.
  const Eigen::Vector3d helper =
      std::abs(dir.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = dir.cross(helper).normalized();
  const Eigen::Vector3d e2 = dir.cross(e1);
  auto to2d = [&](const Eigen::Vector3d& q) {
    const Eigen::Vector3d d = q - p;
    return Eigen::Vector2d(d.dot(e1), d.dot(e2));
  };
  // Barycentric coordinates of the origin; a small negative tolerance gives the cached
  // triangle hysteresis, so points near an edge do not flip triangles every iteration (which
  // would make the estimate cycle instead of converging).
  const Eigen::Vector2d A = to2d(a), B = to2d(b), C = to2d(c);
  const double det = (B - A).x() * (C - A).y() - (B - A).y() * (C - A).x();
  if (!(std::abs(det) > 0.0))
    return false;
  const double l1 = ((-A).x() * (C - A).y() - (-A).y() * (C - A).x()) / det;
  const double l2 = ((B - A).x() * (-A).y() - (B - A).y() * (-A).x()) / det;
  const double tol = -0.05;
  return l1 >= tol && l2 >= tol && 1.0 - l1 - l2 >= tol;
}

// The cached local surface element may be reused: frozen, or the query moved only a small
// fraction of the neighbourhood radius since it was built (so its choice does not depend on
// where the query was several iterations ago — that would bias towards the initial guess).
bool
reusable(const CorrespondenceCache& cache, const Eigen::Vector3d& query)
{
  if (cache.frozen)
    return true;
  const Eigen::Vector3d a(cache.anchor[0], cache.anchor[1], cache.anchor[2]);
  return (query - a).norm() <= static_cast<double>(cache.reuse_radius);
}

// The snap radius of the scratch neighbourhood: kSnapFraction of its radius (0 when empty).
double
snapRadius()
{
  const Scratch& s = scratch();
  return s.sq_dists.empty() ? 0.0 : kSnapFraction * std::sqrt(s.sq_dists.back());
}

// Remembers where (and how far around) a local element was built.
void
anchor(CorrespondenceCache& cache, const Eigen::Vector3d& query)
{
  const Scratch& s = scratch();
  cache.anchor = {
      {static_cast<float>(query.x()), static_cast<float>(query.y()), static_cast<float>(query.z())}};
  cache.reuse_radius = s.sq_dists.empty() ? 0.f : 0.05f * std::sqrt(s.sq_dists.back());
  cache.nearest_sample = s.indices.empty() ? -1 : static_cast<std::int32_t>(s.indices.front());
  cache.snap_radius = static_cast<float>(snapRadius());
}

bool
cachedTriangle(const TargetSurface& target, const CorrespondenceCache& cache,
               std::array<Eigen::Vector3d, 3>& v)
{
  const int n = static_cast<int>(target.size());
  for (std::size_t i = 0; i < 3; ++i) {
    if (cache.vertices[i] < 0 || cache.vertices[i] >= n)
      return false;
    v[i] = target.point(cache.vertices[i]);
  }
  return true;
}

// Index of the projected neighbour nearest to the query (the origin) when it lies within the snap
// radius (see towardsNearestSample), else −1.
int
sampleUnderQuery(const std::vector<Eigen::Vector2d>& projected, double snap_radius)
{
  int nearest = -1;
  double best = snap_radius * snap_radius;
  for (std::size_t i = 0; i < projected.size(); ++i)
    if (projected[i].squaredNorm() <= best) {
      best = projected[i].squaredNorm();
      nearest = static_cast<int>(i);
    }
  return nearest;
}

// A triangle through `apex` and the two nearest neighbours that span a plane with it.
bool
triangleThrough(const std::vector<Eigen::Vector2d>& projected, int apex, std::array<int, 3>& tri)
{
  tri = {{apex, -1, -1}};
  for (std::size_t i = 0; i < projected.size() && tri[2] < 0; ++i) {
    const int j = static_cast<int>(i);
    if (j == apex)
      continue;
    const Eigen::Vector2d a = projected[i] - projected[static_cast<std::size_t>(apex)];
    if (tri[1] < 0) {
      if (a.norm() > 0.0)
        tri[1] = j;
      continue;
    }
    const Eigen::Vector2d b =
        projected[static_cast<std::size_t>(tri[1])] - projected[static_cast<std::size_t>(apex)];
    if (std::abs(a.x() * b.y() - a.y() * b.x()) > 1e-3 * a.norm() * b.norm())
      tri[2] = j;
  }
  return tri[2] >= 0;
}

// Finds the enclosing triangle among the k nearest neighbours, projected along `dir`
// (nullptr: along the neighbourhood's PCA normal). With `on_sample`, a query within the snap
// radius of a sample is supported even on the border of the target (neighbours on one side, no
// enclosing triangle): its surface is measured there, not extrapolated (the element is drawn
// to that sample).
bool
searchTriangle(const Eigen::Vector3d& query, const TargetSurface& target, int k, const Eigen::Vector3d* dir,
               double max_distance, CorrespondenceCache& cache, std::array<Eigen::Vector3d, 3>& v,
               bool on_sample = false)
{
  Scratch& s = scratch();
  int found = 0;
  Eigen::Vector3d eigenvalues;
  for (int attempt = 0; attempt < 2; ++attempt) {
    found = target.nearestKSearch(query, attempt == 0 ? k : kWiden * k, s.indices, s.sq_dists);
    if (found < 3 || !(static_cast<double>(s.sq_dists[0]) <= max_distance * max_distance))
      return false;
    s.indices.resize(static_cast<std::size_t>(found));
    s.sq_dists.resize(static_cast<std::size_t>(found));
    if (!tin::neighbourhoodPca(target, s.indices, found, s.normal, eigenvalues))
      return false;
    if (tin::wellSpread(eigenvalues, kMinSpreadRatio))
      break;
    if (attempt == 1)
      return false;
  }
  const Eigen::Vector3d normal = dir ? *dir : s.normal;
  tin::projectToPlane(target, s.indices, found, query, normal, s.projected);
  const int under = on_sample ? sampleUnderQuery(s.projected, snapRadius()) : -1;
  std::array<int, 3> tri;
  if (under < 0 && !tin::centredSupport(s.projected, kMaxCentroidOffset))
    return false;
  if (!tin::enclosingTriangle(s.projected, tri) && !(under >= 0 && triangleThrough(s.projected, under, tri)))
    return false;
  for (std::size_t i = 0; i < 3; ++i) {
    cache.vertices[i] = s.indices[static_cast<std::size_t>(tri[i])];
    v[i] = target.point(cache.vertices[i]);
  }
  return true;
}

// Local quadric (tin::quadricPatch) of the scratch neighbours, frame axis `axis`; refitted once on
// kWiden·k neighbours when its height is ill-determined (see kMaxHeightVariance).
bool
conditionedQuadric(const Eigen::Vector3d& query, const TargetSurface& target, int k,
                   const Eigen::Vector3d& axis, double& height, Eigen::Vector2d& slope, float& variance)
{
  Scratch& s = scratch();
  double q = 0.0, noise = 0.0;
  int count = static_cast<int>(s.indices.size());
  bool ok = tin::quadricPatch(target, s.indices, count, query, axis, height, slope, &q, &noise) &&
            q <= kMaxHeightVariance;
  if (!ok && count < kWiden * k) {
    count = target.nearestKSearch(query, kWiden * k, s.indices, s.sq_dists);
    s.indices.resize(static_cast<std::size_t>(std::max(count, 0)));
    s.sq_dists.resize(static_cast<std::size_t>(std::max(count, 0)));
    ok = tin::quadricPatch(target, s.indices, count, query, axis, height, slope, &q, &noise) &&
         q <= kMaxHeightVariance;
  }
  variance = static_cast<float>(q * noise);  // σ² of the fitted height at the query
  return ok;
}

// Distance to the farthest of the scratch neighbours (0 when there are none).
double
neighbourhoodRadius()
{
  const Scratch& s = scratch();
  return s.sq_dists.empty() ? 0.0 : std::sqrt(static_cast<double>(s.sq_dists.back()));
}

// Height at (x, y) of the least-squares plane z = a + b dx + c dy through the scratch
// neighbours (their mean height when that plane is ill-determined); NaN without neighbours.
double
heightBelow(const Eigen::Vector3d& query, const TargetSurface& target)
{
  const Scratch& s = scratch();
  if (s.indices.size() < 3)
    return std::numeric_limits<double>::quiet_NaN();
  Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  double mean = 0.0;
  for (const int i : s.indices) {
    const Eigen::Vector3d p = target.point(i);
    const Eigen::Vector3d a(1.0, p.x() - query.x(), p.y() - query.y());
    N += a * a.transpose();
    b += a * p.z();
    mean += p.z();
  }
  mean /= static_cast<double>(s.indices.size());
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(N);
  const Eigen::Vector3d x = ldlt.solve(b);
  return ldlt.info() == Eigen::Success && x.allFinite() && ldlt.rcond() > 1e-10 ? x[0] : mean;
}

// One LZD surface element around `centre`: normal n and point c of the local quadric's tangent
// plane (or the neighbours' plane), and the surface height at (centre.x, centre.y) — also when
// the element is rejected (one-sided neighbours), so the caller can re-centre; NaN without
// neighbours.
bool
lzdElement(const Eigen::Vector3d& centre, const TargetSurface& target, int k, LzdRule::Surface surface,
           double max_distance, CorrespondenceCache& cache, std::array<Eigen::Vector3d, 3>& v,
           Eigen::Vector3d& n, Eigen::Vector3d& c, double& height)
{
  static const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  Scratch& s = scratch();
  s.indices.clear();
  s.sq_dists.clear();
  const bool found = searchTriangle(centre, target, k, &up, max_distance, cache, v, kLzdOnSample);
  if (s.indices.size() >= 3 && !s.sq_dists.empty() &&
      static_cast<double>(s.sq_dists.front()) <= max_distance * max_distance)
    height = heightBelow(centre, target);
  if (!found)
    return false;
  const int count = static_cast<int>(s.indices.size());
  c = Eigen::Vector3d::Zero();
  n = s.normal;
  for (int i = 0; i < count; ++i)
    c += target.point(s.indices[static_cast<std::size_t>(i)]);
  c /= count;
  if (surface == LzdRule::Surface::LOCAL_QUADRIC) {
    // z(x, y) quadric around the query (frame: e1, e2 ⟂ z); its tangent plane at (x', y').
    double h;
    Eigen::Vector2d g;
    if (!conditionedQuadric(centre, target, k, up, h, g, cache.variance))
      return false;
    Eigen::Vector3d e1, e2;
    tin::planeBasis(up, e1, e2);
    c = centre + h * up;
    n = (up - g.x() * e1 - g.y() * e2).normalized();
    height = c.z();
  } else if (std::abs(n.z()) > 1e-6)
    height = c.z() - (n.x() * (centre.x() - c.x()) + n.y() * (centre.y() - c.y())) / n.z();
  return true;
}

}  // namespace

namespace {
// Signed distance along n to the plane (n, p) as one observation.
bool
planeObservation(const Eigen::Vector3d& query, Eigen::Vector3d n, const Eigen::Vector3d& p,
                 double max_distance, double variance, ConjugateObservations& out)
{
  if (n.z() < 0.0)  // a stable orientation; the sign of (u, l) does not change the adjustment
    n = -n;
  const double d = n.dot(query - p);
  if (!std::isfinite(d) || std::abs(d) > max_distance)
    return false;
  out.add(n, d, query - d * n, variance);
  return true;
}

// The element's plane (normal n, point c) in the cache, in float as the cache keeps it.
void
storePlane(const Eigen::Vector3d& n, const Eigen::Vector3d& c, CorrespondenceCache& cache)
{
  cache.plane = {{static_cast<float>(n.x()), static_cast<float>(n.y()), static_cast<float>(n.z()),
                  static_cast<float>(c.x()), static_cast<float>(c.y()), static_cast<float>(c.z())}};
}

// LZD observes along z, so its neighbours must surround the query's vertical. A query far
// above or below the surface (a height offset or a deformation of several point spacings on
// steep relief) has its 3-D nearest neighbours on the nearest slope, one-sided: then the
// search is repeated from the query moved vertically to the height found, until that height
// settles (far above steep relief, the first height is an extrapolation of the nearest slope
// and one step does not reach the surface).
bool
recentredLzdElement(const Eigen::Vector3d& query, const TargetSurface& target, int k,
                    LzdRule::Surface surface, double max_distance, CorrespondenceCache& cache,
                    std::array<Eigen::Vector3d, 3>& v, Eigen::Vector3d& n, Eigen::Vector3d& c)
{
  Eigen::Vector3d centre = query;
  bool ok = false;
  for (int attempt = 0; attempt < kMaxRecentring; ++attempt) {
    double height = std::numeric_limits<double>::quiet_NaN();
    ok = lzdElement(centre, target, k, surface, max_distance, cache, v, n, c, height);
    // Near the surface already when the height moves the centre by less than a quarter of
    // the neighbourhood's radius: a retry would find about the same set. (Not "less than the
    // radius": seen from a query far above, every neighbour is at least that far away.)
    if (attempt + 1 == kMaxRecentring || !std::isfinite(height) ||
        std::abs(height - centre.z()) <= kRecentreFraction * neighbourhoodRadius())
      break;
    centre.z() = height;
  }
  return ok;
}

// Height difference along z from the plane n·(x − p) = 0 to the query as one observation.
bool
heightObservation(const Eigen::Vector3d& query, const Eigen::Vector3d& n, const Eigen::Vector3d& p,
                  double max_distance, float variance, ConjugateObservations& out)
{
  if (!(std::abs(n.z()) > 1e-6 * n.norm()))  // vertical element: no height there
    return false;
  // Plane n·(x − p) = 0 at (query.x, query.y): z = p.z − (n.x dx + n.y dy) / n.z.
  const double z = p.z() - (n.x() * (query.x() - p.x()) + n.y() * (query.y() - p.y())) / n.z();
  const double d = query.z() - z;
  if (!std::isfinite(d) || std::abs(d) > max_distance)
    return false;
  // l = z' − z(x', y'): its gradient w.r.t. x' is (−∂z/∂x, −∂z/∂y, 1), so a horizontal move
  // over a slope changes the height difference (Rosenholm's rigorous LZD linearisation).
  const Eigen::Vector3d gradient(n.x() / n.z(), n.y() / n.z(), 1.0);
  out.add(gradient, d, Eigen::Vector3d(query.x(), query.y(), z), variance);
  return true;
}
}  // namespace

bool
LndRule::findConjugate(const Eigen::Vector3d& query, const TargetSurface& target, double max_distance,
                       CorrespondenceCache& cache, ConjugateObservations& out) const
{
  std::array<Eigen::Vector3d, 3> v;
  const bool cached = cachedTriangle(target, cache, v);
  if (cache.frozen && !cached)
    return false;
  if (surface_ != Surface::TRIANGLE) {
    if (!cached || !reusable(cache, query)) {
      if (!searchTriangle(query, target, neighbours_, nullptr, max_distance, cache, v)) {
        cache.vertices = {{-1, -1, -1}};
        return false;
      }
      // The neighbourhood's least-squares plane (scratch still holds the neighbours).
      Scratch& s = scratch();
      const int count = static_cast<int>(s.indices.size());
      Eigen::Vector3d n = s.normal, c = Eigen::Vector3d::Zero();
      for (int i = 0; i < count; ++i)
        c += target.point(s.indices[static_cast<std::size_t>(i)]);
      c /= count;
      double h;
      Eigen::Vector2d g;
      if (surface_ == Surface::LOCAL_QUADRIC) {
        // Tangent plane of the quadric at the query's projection: point and normal.
        if (!conditionedQuadric(query, target, neighbours_, n, h, g, cache.variance))
          return false;
        Eigen::Vector3d e1, e2;
        tin::planeBasis(n, e1, e2);
        c = query + h * n;
        n = (n - g.x() * e1 - g.y() * e2).normalized();
      }
      anchor(cache, query);
      storePlane(n, c, cache);
    }
    const Eigen::Vector3d n(cache.plane[0], cache.plane[1], cache.plane[2]);
    const Eigen::Vector3d c = towardsNearestSample(
        query, target, cache, Eigen::Vector3d(cache.plane[3], cache.plane[4], cache.plane[5]));
    return planeObservation(query, n.normalized(), c, max_distance, cache.variance, out);
  }
  bool have = cached && cache.frozen;
  if (cached && !have && reusable(cache, query)) {
    const Eigen::Vector3d n = (v[1] - v[0]).cross(v[2] - v[0]);
    have = n.squaredNorm() > 0.0 && projectsInto(query, n.normalized(), v[0], v[1], v[2]);
  }
  if (!have) {
    if (!searchTriangle(query, target, neighbours_, nullptr, max_distance, cache, v)) {
      cache.vertices = {{-1, -1, -1}};
      return false;
    }
    anchor(cache, query);
  }
  const Eigen::Vector3d n = (v[1] - v[0]).cross(v[2] - v[0]);
  if (!(n.norm() > 0.0))
    return false;
  return planeObservation(query, n.normalized(), v[0], max_distance, std::numeric_limits<double>::quiet_NaN(),
                          out);
}

bool
LzdRule::findConjugate(const Eigen::Vector3d& query, const TargetSurface& target, double max_distance,
                       CorrespondenceCache& cache, ConjugateObservations& out) const
{
  static const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  std::array<Eigen::Vector3d, 3> v;
  const bool cached = cachedTriangle(target, cache, v);
  if (cache.frozen && !cached)
    return false;
  Eigen::Vector3d n, p;  // plane normal and a point on it
  if (surface_ != Surface::TRIANGLE) {
    if (!cached || !reusable(cache, query)) {
      Eigen::Vector3d c;
      if (!recentredLzdElement(query, target, neighbours_, surface_, max_distance, cache, v, n, c)) {
        cache.vertices = {{-1, -1, -1}};
        return false;
      }
      anchor(cache, query);
      storePlane(n, c, cache);
    }
    n = Eigen::Vector3d(cache.plane[0], cache.plane[1], cache.plane[2]);
    p = towardsNearestSample(query, target, cache,
                             Eigen::Vector3d(cache.plane[3], cache.plane[4], cache.plane[5]));
  } else {
    const bool have =
        cached && (cache.frozen || (reusable(cache, query) && projectsInto(query, up, v[0], v[1], v[2])));
    if (!have) {
      if (!searchTriangle(query, target, neighbours_, &up, max_distance, cache, v, kLzdOnSample)) {
        cache.vertices = {{-1, -1, -1}};
        return false;
      }
      anchor(cache, query);
    }
    n = (v[1] - v[0]).cross(v[2] - v[0]);
    p = v[0];
  }
  return heightObservation(query, n, p, max_distance, cache.variance, out);
}

}  // namespace pcl_ls3d
