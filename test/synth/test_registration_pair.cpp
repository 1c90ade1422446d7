// Tests of makeRegistrationPair: determinism, truth, densities, overlap, labels.
#include <pcl_ls3d/synth/registration_pair.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_ls3d;
using namespace pcl_ls3d::synth;

namespace {

RegistrationPairSettings
smallSettings(std::uint32_t seed = 3)
{
  RegistrationPairSettings s;
  s.seed = seed;
  s.size_x = 120.0;
  s.size_y = 100.0;
  s.source_density = 1.0;
  s.target_density = 2.0;
  s.overlap = 0.6;
  s.noise_sigma = 0.05;
  s.building_settings.per_hectare = 6.0;
  return s;
}

/// Normal distance of a world point to the true surface, or NaN near building edges (within
/// 1 m, where a noisy point may fall on the other side of a wall).
double
surfaceResidual(const SurfaceModel& surface, const Eigen::Vector3d& p)
{
  const auto& bs = surface.buildings();
  const int inside = bs.find(p.x(), p.y(), 1.0);
  if (inside >= 0) {
    if (!bs.buildings()[inside].contains(p.x(), p.y(), -1.0))
      return std::nan("");
    const Building& b = bs.buildings()[inside];
    // Gable ridge: skip 1 m about the ridge line (kink); elsewhere the roof is a plane.
    if (b.roof == RoofType::GABLE && std::abs(b.toLocal(p.x(), p.y()).y()) < 1.0)
      return std::nan("");
    const double slope = b.roof == RoofType::GABLE ? b.ridge_rise / (0.5 * b.width) : 0.0;
    return (p.z() - b.roofHeight(p.x(), p.y())) / std::sqrt(1.0 + slope * slope);
  }
  const Eigen::Vector3d n = surface.terrain().normal(p.x(), p.y());
  return (p.z() - surface.terrain().height(p.x(), p.y())) * n.z();
}

}  // namespace

// Same seed gives identical clouds; a different seed gives different ones.
TEST(Synth, PairDeterministic)
{
  const auto a = makeRegistrationPair(smallSettings(3));
  const auto b = makeRegistrationPair(smallSettings(3));
  const auto c = makeRegistrationPair(smallSettings(4));
  ASSERT_EQ(a.source->size(), b.source->size());
  ASSERT_EQ(a.target->size(), b.target->size());
  for (std::size_t i = 0; i < a.source->size(); ++i) {
    ASSERT_EQ((*a.source)[i].x, (*b.source)[i].x);
    ASSERT_EQ((*a.source)[i].z, (*b.source)[i].z);
  }
  for (std::size_t i = 0; i < a.target->size(); ++i)
    ASSERT_EQ((*a.target)[i].y, (*b.target)[i].y);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < std::min(a.source->size(), c.source->size()); ++i)
    differ += (*a.source)[i].x != (*c.source)[i].x;
  EXPECT_GT(differ, a.source->size() / 2);
}

// truth.apply(source) and the target both lie on the true surface: RMS normal residual ≈ σ.
TEST(Synth, PairTruthReproducesSurface)
{
  const auto s = smallSettings();
  const auto pair = makeRegistrationPair(s);
  ASSERT_FALSE(pair.source->empty());
  auto rms = [&](const pcl::PointCloud<PointLiDAR>& cloud, const SimilarityTransform& T) {
    double sum = 0.0;
    std::size_t n = 0;
    for (const auto& q : cloud) {
      const double r = surfaceResidual(*pair.surface, T.apply(q.getVector3fMap().cast<double>()));
      if (std::isfinite(r)) {
        sum += r * r;
        ++n;
      }
    }
    EXPECT_GT(n, cloud.size() * 8 / 10);
    return std::sqrt(sum / n);
  };
  // ~12000 samples: the RMS of N(0,σ) is within a few % of σ; the float storage of local
  // coordinates adds < 1e-5 m. Tolerance 10 %.
  EXPECT_NEAR(rms(*pair.target, SimilarityTransform()), s.noise_sigma, 0.1 * s.noise_sigma);
  EXPECT_NEAR(rms(*pair.source, pair.truth), s.noise_sigma, 0.1 * s.noise_sigma);
  // Without the truth the source is clearly off the surface (the test can fail).
  EXPECT_GT(rms(*pair.source, SimilarityTransform()), 2.0 * s.noise_sigma);
}

// Without noise the truth is exact: truth.apply(source) lies on the true surface to float
// rounding (local coordinates ≤ 200 m: float step ≤ 1.5e-5 m), so a systematic error of the
// recorded truth of even 1 mm would fail here.
TEST(Synth, PairTruthExactWithoutNoise)
{
  auto s = smallSettings();
  s.noise_sigma = 0.0;
  const auto pair = makeRegistrationPair(s);
  double worst = 0.0;
  for (const auto& q : *pair.source) {
    const double r = surfaceResidual(*pair.surface, pair.truth.apply(q.getVector3fMap().cast<double>()));
    if (std::isfinite(r))
      worst = std::max(worst, std::abs(r));
  }
  EXPECT_LT(worst, 2e-4);
}

// Point counts follow density × area; the overlap fraction is as requested.
TEST(Synth, PairDensityAndOverlap)
{
  const auto s = smallSettings();
  const auto pair = makeRegistrationPair(s);
  EXPECT_EQ(pair.source->size(), static_cast<std::size_t>(std::lround(s.size_x * s.size_y)));
  EXPECT_EQ(pair.target->size(), static_cast<std::size_t>(std::lround(2.0 * s.size_x * s.size_y)));
  // Density measured in a 40 m × 40 m window inside the target footprint: expected 3200 points,
  // Poisson-like sd ≈ 57; tolerance 5 %.
  const Eigen::Vector2d c = pair.target_footprint.center();
  std::size_t inside = 0;
  for (const auto& q : *pair.target)
    inside += std::abs(q.x - c.x()) < 20.0 && std::abs(q.y - c.y()) < 20.0;
  EXPECT_NEAR(inside / 1600.0, s.target_density, 0.05 * s.target_density);
  std::size_t covered = 0;
  for (const auto& q : *pair.source) {
    const Eigen::Vector3d p = pair.truth.apply(q.getVector3fMap().cast<double>());
    covered += pair.target_footprint.contains(p.head<2>());
  }
  // Binomial with n = 12000, p = 0.6: sd ≈ 0.0045; tolerance 0.02.
  EXPECT_NEAR(static_cast<double>(covered) / pair.source->size(), s.overlap, 0.02);
}

// Labels agree with geometry: ground points on the terrain, roof points well above it.
TEST(Synth, PairLabels)
{
  const auto pair = makeRegistrationPair(smallSettings());
  std::size_t roofs = 0, ground = 0;
  for (const auto& q : *pair.target) {
    const double dz = q.z - pair.surface->terrain().height(q.x, q.y);
    if (q.classification == 2) {
      ++ground;
      EXPECT_LT(std::abs(dz), 0.5);  // 10 σ
    } else {
      ASSERT_EQ(q.classification, 6);
      ++roofs;
      EXPECT_GT(dz, 1.0);  // eaves are ≥ 3 m above the highest footprint terrain
    }
  }
  EXPECT_GT(roofs, 100u);
  EXPECT_GT(ground, roofs);
}

// Georeference: the global truth matrix maps global source points onto global target frame.
TEST(Synth, PairGlobalTruth)
{
  auto s = smallSettings();
  s.origin = Eigen::Vector3d(5e5, 5e6, 100.0);
  const auto pair = makeRegistrationPair(s);
  const Eigen::Matrix4d G = pair.globalTruthMatrix();
  const auto& q = (*pair.source)[0];
  const Eigen::Vector3d local = q.getVector3fMap().cast<double>();
  const Eigen::Vector3d via_local = pair.truth.apply(local) + s.origin;
  const Eigen::Vector3d via_global = G.topLeftCorner<3, 3>() * (local + s.origin) + G.topRightCorner<3, 1>();
  EXPECT_LT((via_local - via_global).norm(), 1e-6);
}

// Impossible settings give empty clouds, not a crash.
TEST(Synth, PairInvalid)
{
  auto s = smallSettings();
  s.overlap = 1.5;
  std::string why;
  EXPECT_FALSE(s.isValid(&why));
  const auto pair = makeRegistrationPair(s);
  ASSERT_TRUE(pair.source && pair.target);
  EXPECT_TRUE(pair.source->empty());
}

#ifdef _OPENMP
#include <omp.h>
// Per-block random streams: the clouds do not depend on the number of threads.
TEST(Synth, PairIndependentOfThreads)
{
  auto s = smallSettings();
  s.target_density = 8.0;  // > one block (32768 points) so several blocks run in parallel
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto a = makeRegistrationPair(s);
  omp_set_num_threads(3);
  const auto b = makeRegistrationPair(s);
  omp_set_num_threads(before);
  ASSERT_EQ(a.target->size(), b.target->size());
  for (std::size_t i = 0; i < a.target->size(); ++i)
    ASSERT_EQ((*a.target)[i].z, (*b.target)[i].z);
}
#endif
