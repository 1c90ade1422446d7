// Weight functions, tuning constants and scales against hand values; IRLS on a planted-outlier
// regression; the M-D estimator's redundancy numbers inside the engine.
#include <pcl_ls3d/estimators/robust_estimator.h>
#include <pcl_ls3d/registration/least_squares_surface_matching.h>
#include <pcl_ls3d/synth/random.h>
#include <pcl_ls3d/synth/registration_pair.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include <Eigen/Dense>

#include <cmath>
#include <numeric>

using namespace pcl_ls3d;

namespace {
Eigen::VectorXd
vec(std::initializer_list<double> v)
{
  Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double x : v)
    out[i++] = x;
  return out;
}

double
weightOf(const RobustEstimator& e, double v, double sigma0)
{
  Eigen::VectorXd w(1);
  e.computeWeights(vec({v}), Eigen::VectorXd(), sigma0, w);
  return w[0];
}
}  // namespace

// Huber: w = 1 inside k σ̂, k / |u| outside (k = 1.345 by default).
TEST(WeightFunctions, HuberHandValues)
{
  const HuberEstimator h(kHuber95, ScaleRule::FIXED, 1.0);
  EXPECT_DOUBLE_EQ(weightOf(h, 0.0, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(weightOf(h, 1.345, 1.0), 1.0);
  EXPECT_NEAR(weightOf(h, 2.0, 1.0), 1.345 / 2.0, 1e-15);
  EXPECT_NEAR(weightOf(h, -4.0, 1.0), 1.345 / 4.0, 1e-15);
  const HuberEstimator h2(kHuber95, ScaleRule::FIXED, 2.0);  // u = v / 2
  EXPECT_NEAR(weightOf(h2, 4.0, 1.0), 1.345 / 2.0, 1e-15);
}

// Tukey (Li eq. 6, 8): w = (1 − u²/c²)², 0 beyond c (c = 4.685).
TEST(WeightFunctions, TukeyHandValues)
{
  const TukeyEstimator t(kTukey95, ScaleRule::FIXED, 2.0);
  EXPECT_DOUBLE_EQ(weightOf(t, 0.0, 1.0), 1.0);
  EXPECT_NEAR(weightOf(t, 4.685, 1.0), 0.5625, 1e-12);  // u = c/2
  EXPECT_NEAR(weightOf(t, -4.685, 1.0), 0.5625, 1e-12);
  EXPECT_DOUBLE_EQ(weightOf(t, 9.37, 1.0), 0.0);  // u = c
  EXPECT_DOUBLE_EQ(weightOf(t, 20.0, 1.0), 0.0);
  EXPECT_NEAR(tukeyWeight(1.0, 4.685), std::pow(1.0 - 1.0 / (4.685 * 4.685), 2), 1e-15);
}

// Li eq. 7: σ̂ = 1.4826 med |v − med v|; the Tukey M uses it by default.
TEST(WeightFunctions, MadScaleAndTukeyUsesIt)
{
  const Eigen::VectorXd v = vec({1, 2, 3, 4, 100});  // med 3, |dev| {2,1,0,1,97}, med 1
  EXPECT_NEAR(madScale(v), 1.4826, 1e-12);
  const TukeyEstimator t;  // MAD scale
  Eigen::VectorXd w(5);
  t.computeWeights(v, Eigen::VectorXd(), 99.0, w);  // σ0 = 99 is ignored
  EXPECT_NEAR(w[0], tukeyWeight(1.0 / 1.4826, 4.685), 1e-12);
  EXPECT_DOUBLE_EQ(w[4], 0.0);
  const Eigen::VectorXd none;
  EXPECT_NEAR(t.scale(WeightingInput(v, none, none, 99.0)), 1.4826, 1e-12);
}

// M-D (Li eq. 10): u = v / (σ̂ √r_i), here σ̂ = σ0 = 1 and r = 0.25: u = 2 v.
TEST(WeightFunctions, MdUsesRedundancyNumbers)
{
  const MdEstimator md;
  const Eigen::VectorXd v = vec({2.0, 2.0}), r = vec({0.25, 1.0}), none;
  Eigen::VectorXd w(2);
  md.weigh(WeightingInput(v, none, r, 1.0), w);
  EXPECT_NEAR(w[0], tukeyWeight(4.0, 4.685), 1e-12);  // low redundancy: judged harder
  EXPECT_NEAR(w[1], tukeyWeight(2.0, 4.685), 1e-12);
  // The engine's σ_vi = σ0 √r_i path gives the same weights.
  Eigen::VectorXd w2(2);
  md.computeWeights(v, vec({0.5, 1.0}), 1.0, w2);
  EXPECT_NEAR(w2[0], w[0], 1e-12);
  EXPECT_NEAR(w2[1], w[1], 1e-12);
  EXPECT_TRUE(md.needsResidualSigmas());
}

// Scale estimators: LMS (Rousseeuw & Leroy), LTS consistency, M-scale and reweighted scale.
TEST(WeightFunctions, ScaleEstimators)
{
  EXPECT_NEAR(lmsScale(1.0, 107, 7), 1.4826 * 1.05, 1e-12);
  EXPECT_NEAR(ltsScale(1.0, 0.5), 2.6482, 2e-3);  // 1 / √(1 − 2 q φ(q) / 0.5), q = 0.6745
  EXPECT_NEAR(ltsScale(4.0, 1.0), 2.0, 1e-12);    // no trimming: plain RMS
  // N(0, 1) sample: every scale is consistent (±4 % on 20000 draws).
  synth::Random rng(3);
  Eigen::VectorXd z(20000);
  for (Eigen::Index i = 0; i < z.size(); ++i)
    z[i] = rng.normal();
  EXPECT_NEAR(madScale(z), 1.0, 0.04);
  EXPECT_NEAR(mScale(z), 1.0, 0.04);
  EXPECT_NEAR(reweightedScale(z, 3.0), 1.0, 0.04);
  // 45 % shifted by 10: the reweighted scale from an inflated start finds the clean σ; the
  // 50 %-breakdown S-scale stays finite but is inflated (its known bias near 50 %).
  Eigen::VectorXd c = z;
  for (Eigen::Index i = 0; i < 9000; ++i)
    c[i] += 10.0;
  EXPECT_NEAR(reweightedScale(c, 2.5), 1.0, 0.05);
  // LMS's final σ* (Rousseeuw & Leroy p. 202): by hand, four residuals ±1 inside 2.5 s0 = 2.5,
  // one at 100 outside, p = 2: √(4 / (4 − 2)); none inside beyond p: 0.
  Eigen::VectorXd h(5);
  h << -1.0, 1.0, -1.0, 1.0, 100.0;
  EXPECT_NEAR(lmsFinalScale(h, 1.0, 2), std::sqrt(2.0), 1e-12);
  EXPECT_EQ(lmsFinalScale(h, 1.0, 4), 0.0);
  // On the 45 % contaminated sample: s0 (inflated by the shifted part) → σ* ≈ the clean σ.
  std::vector<double> sq(static_cast<std::size_t>(c.size()));
  for (Eigen::Index i = 0; i < c.size(); ++i)
    sq[static_cast<std::size_t>(i)] = c[i] * c[i];
  std::nth_element(sq.begin(), sq.begin() + static_cast<std::ptrdiff_t>(sq.size() / 2), sq.end());
  const double s0 = lmsScale(sq[sq.size() / 2], sq.size(), 7);
  EXPECT_GT(s0, 2.0);
  EXPECT_NEAR(lmsFinalScale(c, s0, 7), 1.0, 0.1);
  const double s = mScale(c);
  EXPECT_GT(s, 2.0);
  EXPECT_LT(s, 20.0);
}

// IRLS (Li eqs. 8–9) with each robust estimator on a line with 20 % planted outliers recovers
// the true line; least squares does not.
TEST(WeightFunctions, IrlsOnPlantedOutlierRegression)
{
  const int n = 200;
  Eigen::MatrixXd A(n, 2);
  Eigen::VectorXd y(n);
  synth::Random rng(11);
  for (int i = 0; i < n; ++i) {
    const double x = 0.05 * i;
    A(i, 0) = 1.0;
    A(i, 1) = x;
    y[i] = 2.0 + 0.5 * x + 0.1 * rng.normal() + (i % 5 == 0 ? 5.0 : 0.0);
  }
  auto irls = [&](const RobustEstimator& e) {
    Eigen::Vector2d b = (A.transpose() * A).ldlt().solve(A.transpose() * y);  // LS start
    for (int it = 0; it < 50; ++it) {
      const Eigen::VectorXd v = y - A * b;
      const Eigen::VectorXd none;
      Eigen::VectorXd w(n);
      e.weigh(WeightingInput(v, none, none, 0.0), w);
      const Eigen::MatrixXd W = w.asDiagonal();
      b = (A.transpose() * W * A).ldlt().solve(A.transpose() * W * y);
    }
    return b;
  };
  const Eigen::Vector2d ls = irls(LeastSquaresEstimator());
  EXPECT_GT(std::abs(ls[0] - 2.0), 0.5);  // pulled up by the outliers
  for (const RobustEstimator::Ptr& e :
       {makeRobustEstimator(RobustEstimatorType::TUKEY), makeRobustEstimator(RobustEstimatorType::MD)}) {
    const Eigen::Vector2d b = irls(*e);
    EXPECT_NEAR(b[0], 2.0, 0.05) << e->name();
    EXPECT_NEAR(b[1], 0.5, 0.01) << e->name();
  }
  // Huber's monotone ψ bounds but does not remove the outliers' pull: better than LS only.
  const Eigen::Vector2d hb = irls(HuberEstimator());
  EXPECT_LT(std::abs(hb[0] - 2.0), 0.5 * std::abs(ls[0] - 2.0));
}

// M-D inside the engine: the redundancy numbers of the last solve sum to n − u (here u = 6),
// and the robust weights stay in [0, 1].
TEST(WeightFunctions, MdRedundancyNumbersSumToNMinusU)
{
  synth::RegistrationPairSettings ps;
  ps.size_x = ps.size_y = 60.0;
  ps.overlap = 0.9;
  ps.buildings = false;
  const synth::RegistrationPair pair = synth::makeRegistrationPair(ps);
  LeastSquaresSurfaceMatching<PointLiDAR, PointLiDAR> ls3d;
  ls3d.setInputSource(pair.source);
  ls3d.setInputTarget(pair.target);
  ls3d.setParameterModel(ParameterModel::RIGID_6);
  ls3d.setRobustEstimator(makeRobustEstimator(RobustEstimatorType::MD));
  pcl::PointCloud<PointLiDAR> aligned;
  ls3d.align(aligned);
  ASSERT_TRUE(ls3d.hasConverged()) << ls3d.getReport().message;
  const AdjustmentReport& r = ls3d.getReport();
  ASSERT_FALSE(r.redundancy_numbers.empty());
  const double sum = std::accumulate(r.redundancy_numbers.begin(), r.redundancy_numbers.end(), 0.0);
  EXPECT_NEAR(sum, static_cast<double>(r.redundancy_numbers.size()) - 6.0, 1e-6 * sum);
  for (double w : r.weights) {
    EXPECT_GE(w, 0.0);
    EXPECT_LE(w, 1.0);
  }
  EXPECT_EQ(r.estimator_name, "m-d(4.685)");
}
