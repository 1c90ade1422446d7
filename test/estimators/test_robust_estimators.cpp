// Property check run on every weight-function estimator (w in [0, 1], w(0) = 1, symmetric,
// non-increasing in |v|), plus the exact behaviour of Zuo's 0/1 weight (eq. 15).
#include <pcl_ls3d/estimators/robust_estimator.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

using namespace pcl_ls3d;

namespace {
std::vector<RobustEstimator::Ptr>
allEstimators()
{
  return {std::make_shared<LeastSquaresEstimator>(), std::make_shared<ZuoEstimator>(6.0),
          std::make_shared<ZuoEstimator>(3.0), std::make_shared<HuberEstimator>(),
          std::make_shared<TukeyEstimator>()};
}
}  // namespace

TEST(RobustEstimators, WeightProperties)
{
  // Residuals symmetric about 0, spanning 0..10σ, including 0 itself.
  const int n = 201;
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i)
    v[i] = 0.1 * (i - 100);  // σ0 = 1 below
  for (const auto& e : allEstimators()) {
    Eigen::VectorXd w(n);
    e->computeWeights(v, Eigen::VectorXd(), 1.0, w);
    for (int i = 0; i < n; ++i) {
      EXPECT_GE(w[i], 0.0) << e->name();
      EXPECT_LE(w[i], 1.0) << e->name();
      EXPECT_DOUBLE_EQ(w[i], w[n - 1 - i]) << e->name() << " not symmetric at " << v[i];
      if (i > 100) {
        EXPECT_LE(w[i], w[i - 1] + 1e-15) << e->name() << " increases at " << v[i];
      }
    }
    EXPECT_DOUBLE_EQ(w[100], 1.0) << e->name();
  }
}

TEST(RobustEstimators, ZuoCutsAtKSigma0)
{
  ZuoEstimator zuo(6.0);
  Eigen::VectorXd v(4), w(4);
  v << 0.59, -0.59, 0.61, -0.61;
  zuo.computeWeights(v, Eigen::VectorXd(), 0.1, w);
  EXPECT_EQ(w[0], 1.0);
  EXPECT_EQ(w[1], 1.0);
  EXPECT_EQ(w[2], 0.0);
  EXPECT_EQ(w[3], 0.0);
  // σ0 unknown (first iteration): everything kept.
  zuo.computeWeights(v, Eigen::VectorXd(), 0.0, w);
  EXPECT_EQ(w.sum(), 4.0);
}

// The factory and name parser (as for rules): names, tuning constants, refusals.
TEST(RobustEstimatorFactory, ParsesNamesAndConstants)
{
  std::string why;
  const RobustEstimator::Ptr zuo = parseRobustEstimator("Zuo", &why);
  ASSERT_TRUE(zuo) << why;
  EXPECT_EQ(zuo->name(), "zuo-K(6)");
  EXPECT_EQ(parseRobustEstimator("zuo:7")->name(), "zuo-K(7)");
  EXPECT_EQ(parseRobustEstimator("huber")->name(), "huber(1.345)");
  EXPECT_EQ(parseRobustEstimator("tukey:3.5")->name(), "tukey(3.5)");
  EXPECT_EQ(parseRobustEstimator("ls")->name(), "least-squares");
  // The parsed constant is the one used: Huber's weight at u = 3 with k = 1.5 is 1.5 / 3.
  Eigen::VectorXd v(1), w(1);
  v << 3.0;
  parseRobustEstimator("huber:1.5")->computeWeights(v, Eigen::VectorXd(), 1.0, w);
  EXPECT_DOUBLE_EQ(w[0], 0.5);
  for (const char* bad :
       {"", "median", "zuo:", "zuo:abc", "zuo:6x", "zuo:-1", "zuo:0", "ls:2", "huber:inf"}) {
    why.clear();
    EXPECT_FALSE(parseRobustEstimator(bad, &why)) << bad;
    EXPECT_FALSE(why.empty()) << bad;
  }
}

// A choice is a value: its text reads back to the same type and constant, bit for bit.
TEST(RobustEstimatorFactory, ChoiceTextRoundTrips)
{
  for (const std::string text :
       {"zuo", "zuo:7", "huber:1.5", "tukey", "M", "md:0.1", "ls", "gm:3.3333333333333335"}) {
    RobustEstimatorChoice choice, again;
    ASSERT_TRUE(parseRobustEstimatorChoice(text, choice)) << text;
    ASSERT_TRUE(parseRobustEstimatorChoice(toString(choice), again)) << toString(choice);
    EXPECT_EQ(again.type, choice.type) << text;
    EXPECT_TRUE(std::isnan(choice.constant) ? std::isnan(again.constant) : again.constant == choice.constant)
        << text;
    EXPECT_EQ(makeRobustEstimator(choice)->name(), parseRobustEstimator(text)->name()) << text;
  }
  EXPECT_EQ(toString(RobustEstimatorChoice{}), "zuo");
  RobustEstimatorChoice kept{RobustEstimatorType::HUBER, 2.0};
  std::string why;
  EXPECT_FALSE(parseRobustEstimatorChoice("zuo:-1", kept, &why));
  EXPECT_NE(why.find("positive"), std::string::npos) << why;
  EXPECT_EQ(kept.type, RobustEstimatorType::HUBER);  // untouched on failure
  EXPECT_FALSE(parseRobustEstimatorChoice("ls:2", kept, &why));
}

TEST(RobustEstimatorFactory, MakesEveryShippedEstimator)
{
  for (const RobustEstimatorType type : {RobustEstimatorType::LEAST_SQUARES, RobustEstimatorType::ZUO,
                                         RobustEstimatorType::HUBER, RobustEstimatorType::TUKEY}) {
    const RobustEstimator::Ptr e = makeRobustEstimator(type);
    ASSERT_TRUE(e);
    Eigen::VectorXd v(3), w(3);
    v << 0.0, 0.5, -0.5;
    e->computeWeights(v, Eigen::VectorXd(), 1.0, w);
    EXPECT_EQ(w[0], 1.0) << e->name();
    EXPECT_EQ(w[1], w[2]) << e->name();
  }
}
