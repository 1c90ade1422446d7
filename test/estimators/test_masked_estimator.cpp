// MaskedEstimator: the inner estimator's weights, except for held-out points, which get 0 while
// their residual stays beyond the cut and count again once the fit reaches them; the mask follows
// the points (Observation::point), not the observations' order.
#include <pcl_ls3d/estimators/masked_estimator.h>
#include <pcl_ls3d/estimators/tukey_estimator.h>

#include <gtest/gtest.h>

#include <memory>
#include <vector>

using namespace pcl_ls3d;

namespace {

// Observations of points 0..n-1 in the given order, with residuals v.
ObservationSet
observationsOf(const std::vector<int>& points)
{
  ObservationSet set;
  for (const int p : points) {
    Observation o;
    o.point = p;
    set.items().push_back(o);
  }
  return set;
}

}  // namespace

TEST(MaskedEstimator, HeldOutPointsWeighZeroBeyondTheCut)
{
  constexpr double kScale = 2.0;  // Tukey at a fixed ŝ: cut at 2.5 ŝ = 5
  const auto tukey = std::make_shared<TukeyEstimator>(kTukey95, ScaleRule::FIXED, kScale);
  // Points 1 and 3 are held out; observation order differs from point order.
  const MaskedEstimator masked(tukey, {0, 1, 0, 1});
  const ObservationSet obs = observationsOf({3, 2, 1, 0});
  const Eigen::VectorXd v = (Eigen::VectorXd(4) << 6.0, 6.0, 4.0, 1.0).finished();
  const Eigen::VectorXd none;
  const WeightingInput input(v, none, none, kScale, &obs, 2);
  Eigen::VectorXd w(4), inner(4);
  masked.weigh(input, w);
  tukey->weigh(input, inner);
  EXPECT_EQ(w[0], 0.0);       // point 3: held out, 6 > 5
  EXPECT_EQ(w[1], inner[1]);  // point 2: not held out, Tukey's weight (6 < 4.685 · 2)
  EXPECT_GT(w[1], 0.0);
  EXPECT_EQ(w[2], inner[2]);  // point 1: held out but back within 2.5 ŝ
  EXPECT_EQ(w[3], inner[3]);  // point 0
  EXPECT_DOUBLE_EQ(masked.scale(input), kScale);
  EXPECT_NE(masked.name().find(tukey->name()), std::string::npos);
}

TEST(MaskedEstimator, WithoutObservationsItIsTheInnerEstimator)
{
  const auto tukey = std::make_shared<TukeyEstimator>(kTukey95, ScaleRule::FIXED, 1.0);
  const MaskedEstimator masked(tukey, {1, 1, 1});
  const Eigen::VectorXd v = (Eigen::VectorXd(3) << 0.5, 3.0, 9.0).finished();
  const Eigen::VectorXd none;
  Eigen::VectorXd w(3), inner(3);
  masked.computeWeights(v, none, 1.0, w);
  tukey->computeWeights(v, none, 1.0, inner);
  EXPECT_EQ(w, inner);
  // A mask shorter than the point list leaves the rest alone.
  const ObservationSet obs = observationsOf({5, 6, 7});
  const WeightingInput input(v, none, none, 1.0, &obs, 1);
  masked.weigh(input, w);
  EXPECT_EQ(w, inner);
}
