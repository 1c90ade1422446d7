// 1-D k-means on planted clusters, deterministic results, and degenerate inputs.
#include <pcl_ls3d/stats/kmeans_1d.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace pcl_ls3d::stats;

TEST(KMeans1D, FindsPlantedCentres)
{
  // Three groups like IMRG segment residuals: 0.02 (planar), 0.15 (linear), 0.6 (volumetric),
  // unequal sizes, σ small relative to the gaps. Centre error ≈ σ/√n: tolerance 0.01.
  std::mt19937 rng(3);
  std::vector<double> x;
  const double truth[3] = {0.02, 0.15, 0.6};
  const int count[3] = {300, 40, 120};
  const double sd[3] = {0.005, 0.02, 0.05};
  for (int c = 0; c < 3; ++c) {
    std::normal_distribution<double> d(truth[c], sd[c]);
    for (int i = 0; i < count[c]; ++i)
      x.push_back(d(rng));
  }
  const KMeans1DResult r = kMeans1D(x, 3);
  ASSERT_TRUE(r.valid);
  ASSERT_EQ(r.centres.size(), 3u);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(r.centres[c], truth[c], 0.01) << c;
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.smallest_gap, 0.13, 0.02);
  // Every planted member lands in its own cluster (gaps are > 5σ).
  std::size_t i = 0;
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < count[c]; ++j, ++i)
      EXPECT_EQ(r.assignments[i], c);
  EXPECT_EQ(r.sizes[0], 300u);

  // Deterministic: same input, same answer.
  const KMeans1DResult again = kMeans1D(x, 3);
  EXPECT_EQ(again.centres, r.centres);
}

TEST(KMeans1D, FewDistinctValuesGiveExactCentres)
{
  const KMeans1DResult r = kMeans1D({5.0, 1.0, 5.0, 1.0}, 3);
  ASSERT_TRUE(r.valid);
  ASSERT_EQ(r.centres.size(), 2u);  // only two distinct values
  EXPECT_DOUBLE_EQ(r.centres[0], 1.0);
  EXPECT_DOUBLE_EQ(r.centres[1], 5.0);
  EXPECT_DOUBLE_EQ(r.smallest_gap, 4.0);
  EXPECT_EQ(r.assignments, (std::vector<int>{1, 0, 1, 0}));
  EXPECT_DOUBLE_EQ(r.within_ss, 0.0);
}

TEST(KMeans1D, DegenerateInputs)
{
  EXPECT_FALSE(kMeans1D({}, 3).valid);
  EXPECT_FALSE(kMeans1D({1.0, 2.0}, 0).valid);

  const KMeans1DResult one = kMeans1D({2.0}, 3);
  ASSERT_TRUE(one.valid);
  EXPECT_EQ(one.centres, std::vector<double>{2.0});
  EXPECT_TRUE(std::isnan(one.smallest_gap));

  const KMeans1DResult same = kMeans1D(std::vector<double>(10, 0.3), 3);
  EXPECT_EQ(same.centres.size(), 1u);
  EXPECT_TRUE(std::isnan(same.smallest_gap));

  const KMeans1DResult withNan = kMeans1D({1.0, std::nan(""), 1.2, 9.0, 9.1}, 2);
  ASSERT_EQ(withNan.centres.size(), 2u);
  EXPECT_EQ(withNan.assignments[1], -1);
  EXPECT_NEAR(withNan.centres[0], 1.1, 1e-12);
  EXPECT_NEAR(withNan.centres[1], 9.05, 1e-12);
}
