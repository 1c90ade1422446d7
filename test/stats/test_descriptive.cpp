// Median, MAD and quantiles against values worked out by hand, plus the degenerate inputs.
#include <pcl_ls3d/stats/descriptive.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace pcl_ls3d::stats;

// Exact arithmetic on small integers/halves: tolerances are round-off only (1e-12).
TEST(Descriptive, MedianOddEvenAndUnsorted)
{
  EXPECT_DOUBLE_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_DOUBLE_EQ(median({7.0, -1.0, 100.0, 2.0, 2.0}), 2.0);
}

// The high median is a sample value: the upper of the two middle ones for an even count.
TEST(Descriptive, MedianHighPicksTheUpperMiddleValue)
{
  EXPECT_DOUBLE_EQ(medianHigh({4.0, 1.0, 3.0, 2.0}), 3.0);
  EXPECT_DOUBLE_EQ(medianHigh({3.0, 1.0, 2.0}), median({3.0, 1.0, 2.0}));
  EXPECT_DOUBLE_EQ(medianHigh({-5.0}), -5.0);
  EXPECT_TRUE(std::isnan(medianHigh({})));
  // Against sorting: element n/2 of the sorted sample, for every length up to 9.
  std::vector<double> x;
  for (int n = 1; n <= 9; ++n) {
    x.push_back(static_cast<double>((n * 37) % 11) - 4.5);
    std::vector<double> sorted = x;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_DOUBLE_EQ(medianHigh(x), sorted[sorted.size() / 2]) << "n = " << n;
  }
}

TEST(Descriptive, MadByHand)
{
  // x = 1 1 2 2 4 6 9: median 2, |x − 2| = 1 1 0 0 2 4 7 -> median 1.
  const std::vector<double> x{1, 1, 2, 2, 4, 6, 9};
  EXPECT_DOUBLE_EQ(mad(x), 1.0);
  EXPECT_NEAR(mad(x, true), 1.4826, 1e-12);
  // One huge gross error does not move the MAD (breakdown 50 %).
  EXPECT_DOUBLE_EQ(mad({1, 1, 2, 2, 4, 6, 9e9}), 1.0);
}

TEST(Descriptive, QuantileType7ByHand)
{
  // sorted 10 20 30 40 50: h = 4p. p=0.25 -> 20; p=0.1 -> 10 + 0.4*10 = 14; p=0.9 -> 46.
  const std::vector<double> x{50, 10, 40, 20, 30};
  EXPECT_NEAR(quantile(x, 0.25), 20.0, 1e-12);
  EXPECT_NEAR(quantile(x, 0.1), 14.0, 1e-12);
  EXPECT_NEAR(quantile(x, 0.9), 46.0, 1e-12);
  EXPECT_NEAR(quantile(x, 0.5), median(x), 1e-12);
  EXPECT_DOUBLE_EQ(quantile(x, -1.0), 10.0);  // clamped
  EXPECT_DOUBLE_EQ(quantile(x, 2.0), 50.0);
  const auto q = quantiles(x, {0.0, 0.1, 1.0});
  ASSERT_EQ(q.size(), 3u);
  EXPECT_NEAR(q[1], 14.0, 1e-12);
}

TEST(Descriptive, MeanAndStandardDeviation)
{
  // 2 4 4 4 5 5 7 9: mean 5, Σ(x−5)² = 32, s = √(32/7).
  const std::vector<double> x{2, 4, 4, 4, 5, 5, 7, 9};
  EXPECT_DOUBLE_EQ(mean(x), 5.0);
  EXPECT_NEAR(standardDeviation(x), std::sqrt(32.0 / 7.0), 1e-12);
}

TEST(Descriptive, DegenerateInputsAreDefined)
{
  const std::vector<double> empty;
  EXPECT_TRUE(std::isnan(median(empty)));
  EXPECT_TRUE(std::isnan(mad(empty)));
  EXPECT_TRUE(std::isnan(quantile(empty, 0.5)));
  EXPECT_TRUE(std::isnan(mean(empty)));
  EXPECT_TRUE(std::isnan(standardDeviation({1.0})));
  EXPECT_EQ(quantiles(empty, {0.5, 0.9}).size(), 2u);

  EXPECT_DOUBLE_EQ(median({4.2}), 4.2);
  EXPECT_DOUBLE_EQ(mad({4.2}), 0.0);
  EXPECT_DOUBLE_EQ(quantile({4.2}, 0.7), 4.2);

  const std::vector<double> same(9, 3.0);
  EXPECT_DOUBLE_EQ(median(same), 3.0);
  EXPECT_DOUBLE_EQ(mad(same, true), 0.0);
  EXPECT_DOUBLE_EQ(standardDeviation(same), 0.0);
}
