// The neighbour-difference noise scale: it recovers the point noise of a residual field whatever
// smooth part the field carries (a tilt, a raised patch), where the MAD of the residuals does not;
// duplicates, missing residuals and tiny inputs are handled.
#include <pcl_ls3d/estimators/neighbour_noise.h>
#include <pcl_ls3d/estimators/robust_scale.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace pcl_ls3d;

namespace {

constexpr double kSigma = 2.0;

// A 60 × 60 grid of spacing 1 with residual = smooth(x, y) + N(0, σ).
struct Field
{
  template <typename Smooth>
  Field(Smooth smooth, std::uint32_t seed)
  {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, kSigma);
    for (int y = 0; y < 60; ++y)
      for (int x = 0; x < 60; ++x) {
        points.emplace_back(x, y, 0.1 * x);
        residuals.push_back(smooth(x, y) + noise(rng));
      }
  }
  double
  mad() const
  {
    return madScale(
        Eigen::Map<const Eigen::VectorXd>(residuals.data(), static_cast<Eigen::Index>(residuals.size())));
  }
  std::vector<Eigen::Vector3d> points;
  std::vector<double> residuals;
};

}  // namespace

TEST(NeighbourNoise, WhiteNoiseAlone)
{
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const Field f([](int, int) { return 0.0; }, seed);
    EXPECT_NEAR(neighbourDifferenceScale(f.points, f.residuals), kSigma, 0.08 * kSigma) << "seed " << seed;
  }
}

// A tilt of 20 σ across the grid and a third of it raised by 5 σ: the MAD sees them, σ_d does not.
TEST(NeighbourNoise, SmoothPartsCancel)
{
  const Field f(
      [](int x, int y) { return (x < 30 && y < 40 ? 5.0 * kSigma : 0.0) + 20.0 * kSigma * (x + y) / 118.0; },
      4);
  const double sd = neighbourDifferenceScale(f.points, f.residuals);
  EXPECT_NEAR(sd, kSigma, 0.12 * kSigma);
  EXPECT_GT(f.mad(), 3.0 * kSigma);
}

// Every point twice at the same position with the same residual: a duplicate is no neighbour.
TEST(NeighbourNoise, DuplicatesAreNoNeighbours)
{
  Field f([](int, int) { return 0.0; }, 5);
  const std::size_t n = f.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    f.points.push_back(f.points[i]);
    f.residuals.push_back(f.residuals[i]);
  }
  EXPECT_NEAR(neighbourDifferenceScale(f.points, f.residuals), kSigma, 0.1 * kSigma);
}

TEST(NeighbourNoise, MissingResidualsAndTinyInputs)
{
  Field f([](int, int) { return 0.0; }, 6);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < f.residuals.size(); i += 3)
    f.residuals[i] = nan;                        // a third without a residual
  f.points[1] = Eigen::Vector3d::Constant(nan);  // a non-finite point
  const double sd = neighbourDifferenceScale(f.points, f.residuals);
  EXPECT_TRUE(std::isfinite(sd));
  EXPECT_NEAR(sd, kSigma, 0.12 * kSigma);
  EXPECT_EQ(neighbourDifferenceScale({}, {}), 0.0);
  EXPECT_EQ(neighbourDifferenceScale({Eigen::Vector3d::Zero()}, {1.0}), 0.0);
  EXPECT_EQ(neighbourDifferenceScale({Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}, {1.0, 2.0}), 0.0);
  EXPECT_NEAR(neighbourDifferenceScale({Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()}, {1.0, 3.0}),
              1.4826 * 2.0 / std::sqrt(2.0), 1e-12);
}
