// Baarda data snooping: planted gross errors must be removed, the good values kept; the w-test
// on regression residuals is checked against redundancy numbers computed independently (hat
// matrix of a straight-line fit with Eigen).
#include <pcl_ls3d/stats/data_snooping.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace pcl_ls3d::stats;

TEST(DataSnooping, CriticalValues)
{
  // Standard normal table: two-sided 5 % -> 1.95996, 0.1 % -> 3.29053.
  EXPECT_NEAR(normalCriticalValue(0.05), 1.959964, 1e-5);
  EXPECT_NEAR(normalCriticalValue(0.001), 3.290527, 1e-5);
  EXPECT_TRUE(std::isnan(normalCriticalValue(0.0)));
  EXPECT_TRUE(std::isnan(normalCriticalValue(1.5)));
}

TEST(DataSnooping, RemovesPlantedGrossErrorsAndKeepsTheRest)
{
  // 200 values N(1, 0.1) (IMRG-like neighbour distances) and 6 gross ones in 5..40 (D2 type).
  std::mt19937 rng(42);
  std::normal_distribution<double> good(1.0, 0.1);
  std::vector<double> x;
  for (int i = 0; i < 200; ++i)
    x.push_back(good(rng));
  const std::vector<double> gross{5.0, 40.0, 12.0, 7.5, 25.0, 9.0};
  for (double g : gross)
    x.push_back(g);

  const DataSnoopingResult r = dataSnooping(x);
  ASSERT_TRUE(r.valid);
  // Every planted value (indices 200..205) is rejected.
  for (std::size_t i = 200; i < 206; ++i)
    EXPECT_TRUE(std::binary_search(r.rejected.begin(), r.rejected.end(), i)) << i;
  // 6 planted + at most 2 good ones lost by chance (α0 = 0.001 over 200 values: ~0.2 expected).
  EXPECT_LE(r.rejected.size(), 8u);
  EXPECT_EQ(r.kept.size() + r.rejected.size(), x.size());
  // The final estimates describe the good population (σ/√200 ≈ 0.007, use 0.05 and 0.03).
  EXPECT_NEAR(r.mean, 1.0, 0.05);
  EXPECT_NEAR(r.sigma, 0.1, 0.03);
  EXPECT_LT(r.max_kept, 1.0 + 4.0 * 0.1);  // max of the good values: about 1 + 3σ
  EXPECT_GT(r.max_kept, 1.0 + 1.5 * 0.1);
  EXPECT_LE(r.max_w, r.critical_value);
  EXPECT_NEAR(r.critical_value, 3.2905, 1e-3);
}

TEST(DataSnooping, KnownSigmaAndOneSidedUpper)
{
  // With σ known, a value 5σ below the mean is rejected two-sided but kept one-sided-upper.
  std::vector<double> x(50, 0.0);
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = (i % 2 ? 0.01 : -0.01);
  x.push_back(-0.5);
  DataSnoopingSettings s;
  s.sigma_apriori = 0.1;
  EXPECT_EQ(dataSnooping(x, s).rejected, std::vector<std::size_t>{50});
  s.one_sided_upper = true;
  EXPECT_TRUE(dataSnooping(x, s).rejected.empty());
}

TEST(DataSnooping, DegenerateInputs)
{
  const DataSnoopingResult e = dataSnooping({});
  EXPECT_FALSE(e.valid);
  EXPECT_TRUE(e.kept.empty());
  EXPECT_TRUE(std::isnan(e.max_kept));

  const DataSnoopingResult one = dataSnooping({2.5});
  ASSERT_TRUE(one.valid);
  EXPECT_EQ(one.kept.size(), 1u);
  EXPECT_DOUBLE_EQ(one.max_kept, 2.5);
  EXPECT_DOUBLE_EQ(one.sigma, 0.0);

  const DataSnoopingResult same = dataSnooping(std::vector<double>(20, 1.25));
  EXPECT_TRUE(same.rejected.empty());
  EXPECT_DOUBLE_EQ(same.max_kept, 1.25);

  // NaN is rejected up front; never returned as a kept value.
  const double nan = std::nan("");
  const DataSnoopingResult withNan = dataSnooping({1.0, nan, 1.1, 0.9});
  EXPECT_EQ(withNan.rejected, std::vector<std::size_t>{1});
  EXPECT_DOUBLE_EQ(withNan.max_kept, 1.1);

  // min_kept is honoured even if everything would be rejected.
  DataSnoopingSettings s;
  s.sigma_apriori = 1e-9;
  s.min_kept = 2;
  EXPECT_EQ(dataSnooping({1.0, 2.0, 3.0, 4.0}, s).kept.size(), 2u);
}

TEST(DataSnooping, BaardaOnLineFitFindsPlantedOutlier)
{
  // y = 2 + 0.5 t + N(0, 0.05²), one observation shifted by 1.0 (20 σ). The redundancy
  // numbers r_i = 1 − h_ii come from the hat matrix H = A (AᵀA)⁻¹ Aᵀ, computed here.
  const int n = 30;
  const double sigma = 0.05;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, sigma);
  Eigen::MatrixXd A(n, 2);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) {
    A(i, 0) = 1.0;
    A(i, 1) = i;
    y(i) = 2.0 + 0.5 * i + noise(rng);
  }
  y(17) += 1.0;

  std::vector<bool> active(n, true);
  std::vector<int> rejected;
  const double k = normalCriticalValue(0.001);
  for (int round = 0; round < 5; ++round) {
    std::vector<int> rows;
    for (int i = 0; i < n; ++i)
      if (active[i])
        rows.push_back(i);
    Eigen::MatrixXd Aa(rows.size(), 2);
    Eigen::VectorXd ya(rows.size());
    for (std::size_t j = 0; j < rows.size(); ++j) {
      Aa.row(j) = A.row(rows[j]);
      ya(j) = y(rows[j]);
    }
    const Eigen::MatrixXd N_inv = (Aa.transpose() * Aa).inverse();
    const Eigen::VectorXd v = Aa * (N_inv * Aa.transpose() * ya) - ya;
    std::vector<double> vv(rows.size()), rr(rows.size());
    for (std::size_t j = 0; j < rows.size(); ++j) {
      vv[j] = v(j);
      rr[j] = 1.0 - Aa.row(j) * N_inv * Aa.row(j).transpose();
    }
    // Σ r_i = n − u is an identity of least squares: checks the redundancy input.
    double sum_r = 0.0;
    for (double r : rr)
      sum_r += r;
    EXPECT_NEAR(sum_r, static_cast<double>(rows.size()) - 2.0, 1e-9);

    const BaardaTestResult t = baardaTest(vv, rr, {}, sigma, k);
    ASSERT_EQ(t.w.size(), rows.size());
    if (t.worst < 0)
      break;
    rejected.push_back(rows[static_cast<std::size_t>(t.worst)]);
    active[rows[static_cast<std::size_t>(t.worst)]] = false;
  }
  EXPECT_EQ(rejected, std::vector<int>{17});
}

TEST(DataSnooping, BaardaRejectsBadArguments)
{
  EXPECT_EQ(baardaTest({1.0, 2.0}, {0.5}, {}, 1.0, 3.29).worst, -1);
  EXPECT_TRUE(baardaTest({1.0}, {0.5}, {}, 0.0, 3.29).w.empty());
  // r_i = 0 (uncontrolled observation) is not tested, even with a huge residual.
  const BaardaTestResult t = baardaTest({100.0, 0.1}, {0.0, 0.9}, {1.0, 1.0}, 1.0, 3.29);
  EXPECT_FALSE(t.tested[0]);
  EXPECT_EQ(t.worst, -1);
  // w = v / (σ0 √(r/p)) by hand: 4 / (2 √(0.25/4)) = 8.
  EXPECT_NEAR(baardaTest({4.0}, {0.25}, {4.0}, 2.0, 3.29).w[0], 8.0, 1e-12);
}

namespace {
/// Independent textbook elimination: recompute mean and σ over all kept values every round and
/// remove the first value (input order) of largest |w| (the O(n · rounds) definition).
std::vector<std::size_t>
naiveRejected(const std::vector<double>& x, double k, bool one_sided)
{
  std::vector<std::size_t> kept(x.size()), rejected;
  for (std::size_t i = 0; i < x.size(); ++i)
    kept[i] = i;
  while (kept.size() > 3) {
    double m = 0.0, ss = 0.0;
    for (auto i : kept)
      m += x[i];
    m /= kept.size();
    for (auto i : kept)
      ss += (x[i] - m) * (x[i] - m);
    const double s = std::sqrt(ss / (kept.size() - 1));
    if (s <= 0.0)
      break;
    double best = 0.0;
    std::size_t worst = 0;
    for (std::size_t j = 0; j < kept.size(); ++j) {
      const double d = x[kept[j]] - m;
      if (one_sided && d <= 0.0)
        continue;
      if (std::abs(d) / s > best) {
        best = std::abs(d) / s;
        worst = j;
      }
    }
    if (best <= k)
      break;
    rejected.push_back(kept[worst]);
    kept.erase(kept.begin() + worst);
  }
  std::sort(rejected.begin(), rejected.end());
  return rejected;
}
}  // namespace

TEST(DataSnooping, IncrementalEliminationMatchesTheNaiveDefinition)
{
  // Heavy-tailed samples (many rounds), duplicates and both tails: the sorted-range
  // implementation must reject exactly what the round-by-round recomputation rejects.
  std::mt19937 rng(7);
  std::lognormal_distribution<double> heavy(0.0, 1.2);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> x;
    for (int i = 0; i < 300; ++i)
      x.push_back(trial % 2 ? heavy(rng) : noise(rng) * (i % 17 == 0 ? 30.0 : 1.0));
    x.push_back(x[5]);  // exact duplicates
    x.push_back(x[5]);
    for (const bool one_sided : {false, true}) {
      DataSnoopingSettings s;
      s.one_sided_upper = one_sided;
      const DataSnoopingResult r = dataSnooping(x, s);
      const auto ref = naiveRejected(x, r.critical_value, one_sided);
      EXPECT_GT(ref.size(), 0u);
      EXPECT_EQ(r.rejected, ref) << "trial " << trial << " one-sided " << one_sided;
      double mx = -1e300;
      for (auto i : r.kept)
        mx = std::max(mx, x[i]);
      EXPECT_EQ(r.max_kept, mx);
    }
  }
}
