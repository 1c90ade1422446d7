// The pair's source block from the guess (sourceBlockFromGuess, adjustment_settings.h): the
// block must reproduce the guess in the clouds' own coordinates (checked on points mapped both
// ways, independently of the block's parameterisation), start its translations at 0, take L_e
// from the guess or from the settings, and hold fixed parameters exactly at L_e.
#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/common/similarity_transform.h>

#include <gtest/gtest.h>

using namespace pcl_ls3d;

namespace {

Eigen::Matrix4d
someGuess()
{
  SimilarityTransform s;
  s.t = Eigen::Vector3d(5.0, -3.0, 2.0);
  s.phi = 0.01;
  s.omega = -0.02;
  s.kappa = 0.3;
  s.m = 1.02;
  return s.matrix();
}

/// x' of the block: o_t + t + m R (x − o_s).
Eigen::Vector3d
mapByBlock(const ParameterBlock& b, const Eigen::Vector3d& x)
{
  return b.output_origin + SimilarityTransform(b.values).apply(x - b.input_origin);
}

}  // namespace

TEST(SourceBlockFromGuess, ReproducesTheGuessAboutTheReductionOrigin)
{
  const Eigen::Matrix4d guess = someGuess();
  const Eigen::Vector3d o_s(10.0, 20.0, 3.0);
  const ParameterBlock b = sourceBlockFromGuess(guess, o_s, AdjustmentSettings::similarity7());

  EXPECT_TRUE(b.input_origin.isApprox(o_s));
  EXPECT_LT((b.output_origin - (guess * o_s.homogeneous()).head<3>()).norm(), 1e-12);
  EXPECT_EQ(b.values[TX], 0.0);
  EXPECT_EQ(b.values[TY], 0.0);
  EXPECT_EQ(b.values[TZ], 0.0);
  for (const Eigen::Vector3d& x :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(-40, 7, 12), Eigen::Vector3d(100, -50, -3)})
    EXPECT_LT((mapByBlock(b, x) - (guess * x.homogeneous()).head<3>()).norm(), 1e-9) << x.transpose();
  // L_e from the guess (the default), P_e from the settings.
  EXPECT_TRUE(b.apriori_values.isApprox(b.values));
  EXPECT_TRUE(b.apriori_weights.isApprox(AdjustmentSettings::similarity7().apriori_weights));
}

TEST(SourceBlockFromGuess, FixedParametersStartExactlyAtTheirAprioriValues)
{
  AdjustmentSettings rigid = AdjustmentSettings::rigid6();  // scale fixed
  rigid.apriori_from_guess = false;
  rigid.apriori_values = (Vector7d() << 0.5, 0, 0, 0, 0, 0, 1.0).finished();
  const ParameterBlock b = sourceBlockFromGuess(someGuess(), Eigen::Vector3d(1, 2, 3), rigid);

  ASSERT_TRUE(rigid.isFixed(SCALE));
  EXPECT_EQ(b.values[SCALE], 1.0);           // the guess's scale is 1.02: fixed means L_e, exactly
  EXPECT_NEAR(b.values[KAPPA], 0.3, 1e-12);  // free parameters keep the guess
  EXPECT_EQ(b.values[TX], 0.0);              // ... and start at 0, not at L_e's 0.5
  EXPECT_TRUE(b.apriori_values.isApprox(rigid.apriori_values));
}

TEST(FreeParameterCount, CountsWhatThePresetsAndSoftWeightsLeaveFree)
{
  EXPECT_EQ(freeParameterCount(parameterModelWeights(ParameterModel::SIMILARITY_7)), 7);
  EXPECT_EQ(freeParameterCount(parameterModelWeights(ParameterModel::RIGID_6)), 6);
  EXPECT_EQ(freeParameterCount(parameterModelWeights(ParameterModel::TRANSLATION_3)), 3);
  EXPECT_EQ(freeParameterCount(parameterModelWeights(ParameterModel::HEIGHT_1)), 1);
  // A soft constraint (finite weight) still leaves the parameter to the adjustment.
  AdjustmentSettings soft = AdjustmentSettings::rigid6();
  soft.apriori_weights[KAPPA] = 1e6;
  soft.fixParameter(TZ);
  EXPECT_EQ(freeParameterCount(soft.apriori_weights), 5);
}
