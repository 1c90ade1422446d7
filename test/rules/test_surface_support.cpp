// Overlap handling and conditioning of the LND / LZD local surfaces, through the public rule API
// only: no observation at or beyond the border of the sampled target (partial overlap), none or
// a correct one from a neighbourhood of two nearly coincident scan lines (zig-zag swath edge).
#include <pcl_ls3d/rules/lnd_rule.h>
#include <pcl_ls3d/rules/lzd_rule.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_ls3d;

namespace {

// A smooth curved surface (exactly quadratic in z(x, y)).
double
bowl(double x, double y)
{
  return 2.0 + 0.3 * x - 0.2 * y + 0.05 * x * x - 0.04 * x * y + 0.08 * y * y;
}

Eigen::Vector3d
bowlNormal(double x, double y)
{
  return Eigen::Vector3d(-(0.3 + 0.1 * x - 0.04 * y), -(-0.2 - 0.04 * x + 0.16 * y), 1.0).normalized();
}

// Samples every 0.5 m for x <= 0 only: the target's border is the line x = 0.
PointVectorTargetSurface
halfPlane()
{
  std::vector<Eigen::Vector3d> pts;
  for (int i = -24; i <= 0; ++i)
    for (int j = -24; j <= 24; ++j)
      pts.emplace_back(0.5 * i, 0.5 * j, bowl(0.5 * i, 0.5 * j));
  return PointVectorTargetSurface(pts);
}

const ConjugateRule::Ptr kRules[] = {std::make_shared<LndRule>(), std::make_shared<LzdRule>()};

}  // namespace

TEST(SurfaceSupport, NoObservationAtOrBeyondTheTargetBorder)
{
  const auto target = halfPlane();
  for (const auto& rule : kRules) {
    // Well inside: an observation, ~0 for a query on the surface (sub-mm: quadric fit frame).
    {
      CorrespondenceCache cache;
      ConjugateObservations out;
      const Eigen::Vector3d q(-5.1, 0.3, bowl(-5.1, 0.3));
      ASSERT_TRUE(rule->findConjugate(q, target, 5.0, cache, out)) << rule->name();
      EXPECT_NEAR(out.items[0].distance, 0.0, 1e-3) << rule->name();
    }
    // Beyond the last sample column, within reach of the samples: the neighbours lie on one
    // side only, so the surface there would be extrapolated — no observation. (A query exactly
    // on the last column is accepted by the centroid-offset test of the rules: its half-disc
    // neighbourhood includes the column itself.)
    for (double x : {0.3, 1.0, 3.0}) {
      CorrespondenceCache cache;
      ConjugateObservations out;
      const Eigen::Vector3d q(x, 0.3, bowl(x, 0.3));
      EXPECT_FALSE(rule->findConjugate(q, target, 5.0, cache, out) && out.count > 0)
          << rule->name() << " x = " << x;
    }
  }
}

TEST(SurfaceSupport, TwoCloseScanLinesGiveNoArbitrarySurface)
{
  // Only two scan lines along y, 0.1 m apart, heights off the surface by ±1 cm: the surface across
  // the lines is undetermined. A rule may refuse the query or must get it right; an arbitrary
  // tilted patch (the zig-zag failure) fails both.
  std::vector<Eigen::Vector3d> pts;
  for (int i = -40; i <= 40; ++i)
    for (int line = 0; line < 2; ++line) {
      const double x = 0.1 * line, y = 0.5 * i;
      pts.emplace_back(x, y, bowl(x, y) + ((i + line) % 2 ? 0.01 : -0.01));
    }
  const PointVectorTargetSurface target(pts);
  const Eigen::Vector3d n = bowlNormal(0.05, 0.25);
  const Eigen::Vector3d q = Eigen::Vector3d(0.05, 0.25, bowl(0.05, 0.25)) + 0.1 * n;
  for (const auto& rule : kRules) {
    CorrespondenceCache cache;
    ConjugateObservations out;
    if (!rule->findConjugate(q, target, 5.0, cache, out) || out.count == 0)
      continue;
    const Eigen::Vector3d u = out.items[0].direction.normalized();
    EXPECT_GT(std::abs(u.dot(n)), std::cos(5.0 * M_PI / 180.0)) << rule->name();
  }
}

// A DEM's own edge: a query on a sample of the border (a corner, an edge node) is measured there,
// not extrapolated, so LZD observes it (its height difference is the offset), while a query a
// fraction of the spacing beyond the corner, off any sample, still has none. LND keeps the
// stricter rule (no observation on the border).
TEST(SurfaceSupport, LzdObservesSamplesOnTheTargetBorder)
{
  const auto target = halfPlane();
  const LzdRule lzd;
  const LndRule lnd;
  for (const Eigen::Vector2d& xy :
       {Eigen::Vector2d(0.0, -12.0), Eigen::Vector2d(0.0, 3.5), Eigen::Vector2d(-12.0, 12.0)}) {
    const Eigen::Vector3d q(xy.x(), xy.y(), bowl(xy.x(), xy.y()) + 0.25);
    CorrespondenceCache cache;
    ConjugateObservations out;
    ASSERT_TRUE(lzd.findConjugate(q, target, 5.0, cache, out) && out.count > 0) << xy.transpose();
    EXPECT_NEAR(out.items[0].distance, 0.25, 1e-3) << xy.transpose();
    CorrespondenceCache lnd_cache;
    ConjugateObservations lnd_out;
    if (xy.x() == 0.0 && std::abs(xy.y()) == 12.0) {  // a corner: a quarter disc
      EXPECT_FALSE(lnd.findConjugate(q, target, 5.0, lnd_cache, lnd_out) && lnd_out.count > 0);
    }
  }
  for (const Eigen::Vector2d& xy : {Eigen::Vector2d(0.2, -12.2), Eigen::Vector2d(0.25, 3.5)}) {
    const Eigen::Vector3d q(xy.x(), xy.y(), bowl(xy.x(), xy.y()));
    CorrespondenceCache cache;
    ConjugateObservations out;
    EXPECT_FALSE(lzd.findConjugate(q, target, 5.0, cache, out) && out.count > 0) << xy.transpose();
  }
}
