// SampleConsensusModelSurfaceMatching driven by PCL's own estimators, unchanged: with 40 % of
// Li's surface deformed by 25 σ at a corner, pcl::LeastMedianSquares, pcl::RandomSampleConsensus
// and pcl::MEstimatorSampleConsensus find the stable part, and the model's IRLS refinement
// (optimizeModelCoefficients) brings the transform within 0.5 σ of the truth at every grid node.
#include <pcl_ls3d/evaluation/transform_error.h>
#include <pcl_ls3d/registration/least_squares_surface_matching.h>
#include <pcl_ls3d/sample_consensus/sac_model_surface_matching.h>
#include <pcl_ls3d/sample_consensus/subset_search.h>
#include <pcl_ls3d/synth/li_surface.h>

#include <pcl/sample_consensus/lmeds.h>
#include <pcl/sample_consensus/msac.h>
#include <pcl/sample_consensus/ransac.h>

#include <gtest/gtest.h>

#include <algorithm>

using namespace pcl_ls3d;
using Model = SampleConsensusModelSurfaceMatching<PointLiDAR>;

namespace {

synth::LiSurface
deformedSurface(double percent, double c, synth::DeformationPosition position)
{
  synth::LiSurfaceSettings s;
  s.deformation_percent = percent;
  s.deformation_c = c;
  s.position = position;
  return synth::makeLiSurface(s);
}

/// Li's first step: an all-points LHD (LZD rule, 6 parameters, least squares) from the identity,
/// which brings the surfaces close (biased by the deformation).
Eigen::Matrix4d
lhdStart(const synth::LiSurface& li)
{
  LeastSquaresSurfaceMatching<PointLiDAR, PointLiDAR> lhd;
  AdjustmentSettings all_points = AdjustmentSettings::rigid6();
  all_points.automatic_reach = false;  // all points, deformed ones too, as in Li's first step
  lhd.setAdjustmentSettings(all_points);
  lhd.setConjugateRule(ConjugateRuleType::LZD);
  lhd.setRobustEstimator(std::make_shared<LeastSquaresEstimator>());
  lhd.setInputSource(li.mate);
  lhd.setInputTarget(li.reference);
  pcl::PointCloud<PointLiDAR> aligned;
  lhd.align(aligned);
  return lhd.getReport().transformation;
}

/// Largest displacement of a grid node between the estimate and the truth, in σ.
double
maxErrorSigma(const Eigen::Matrix4d& T, const synth::LiSurface& li, double sigma)
{
  Eigen::Matrix3Xd pts(3, static_cast<Eigen::Index>(li.mate->size()));
  for (std::size_t i = 0; i < li.mate->size(); ++i)
    pts.col(static_cast<Eigen::Index>(i)) = (*li.mate)[i].getVector3fMap().cast<double>();
  return evaluation::computeTransformError(T, li.truth.matrix(), pts).max / sigma;
}

}  // namespace

TEST(SacModelSurfaceMatching, ShapeAndCoefficients)
{
  const synth::LiSurface li = deformedSurface(0.0, 0.0, synth::DeformationPosition::MIDDLE);
  Model model(li.mate, li.reference);
  ASSERT_TRUE(model.linearize(li.truth.matrix()));
  EXPECT_EQ(model.getModelType(), pcl::SACMODEL_REGISTRATION);
  EXPECT_EQ(model.getSampleSize(), 7u);
  EXPECT_EQ(model.getModelSize(), 7u);
  EXPECT_EQ(model.getLinearization().freeParameters(), 6);  // LHD: m fixed
  // At the truth every node lies on a reference node, those on the border too (one-sided
  // neighbourhoods, but the height is measured there): every node has an observation.
  EXPECT_EQ(model.getLinearization().size(), li.mate->size());
  // Coefficients and matrices convert both ways.
  const Eigen::VectorXf c = model.toCoefficients(li.truth.matrix());
  EXPECT_LT((model.toMatrix(c) - li.truth.matrix()).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_FALSE(model.setSampleSize(5));  // cannot determine 6 parameters
  EXPECT_TRUE(model.setSampleSize(6));
}

TEST(SacModelSurfaceMatching, LeastMedianSquaresRecoversTruthWith40PercentDeformed)
{
  const synth::LiSurface li = deformedSurface(40.0, 25.0, synth::DeformationPosition::UPPER_RIGHT);
  const double sigma = 20.0;
  Model::Ptr model(new Model(li.mate, li.reference));
  const Eigen::Matrix4d start = lhdStart(li);
  EXPECT_GT(maxErrorSigma(start, li, sigma), 5.0);  // least squares is pulled far off
  ASSERT_TRUE(model->linearize(start));
  pcl::LeastMedianSquares<PointLiDAR> lmeds(model, 3.0 * sigma);
  lmeds.setMaxIterations(subsetsForConfidence(0.4, 0.999, 7));
  ASSERT_TRUE(lmeds.computeModel());
  Eigen::VectorXf c;
  lmeds.getModelCoefficients(c);
  // The residuals are linearised at the biased start, so the first estimate is only nearer the
  // truth; a second search linearised there (Li's procedure in robust_matching.h does the
  // same) and an IRLS refinement over its inliers reach it.
  Eigen::Matrix4d T = model->toMatrix(c);
  const double first = maxErrorSigma(T, li, sigma);
  EXPECT_LT(first, 0.5 * maxErrorSigma(start, li, sigma));
  ASSERT_TRUE(model->linearize(T));  // a new linearisation point (and reduced frame)
  ASSERT_TRUE(lmeds.computeModel());
  lmeds.getModelCoefficients(c);
  T = model->toMatrix(c);
  // Near, not at the truth: a 7-point fit scored by the median is imprecise (LMS converges at
  // n^(-1/3)); this search and the first land 1.5–2.5 σ off at the far corner, in either order
  // depending on which nodes are observed. The IRLS over its inliers is what reaches the truth.
  EXPECT_LT(maxErrorSigma(T, li, sigma), 3.0);
  pcl::Indices inliers;
  model->selectWithinDistance(c, 3.0 * sigma, inliers);
  EXPECT_GT(inliers.size(), 0.5 * li.mate->size());
  Eigen::VectorXf refined;
  model->optimizeModelCoefficients(inliers, c, refined);
  EXPECT_LT(maxErrorSigma(model->toMatrix(refined), li, sigma), 0.5);
  // Inliers are (almost) exactly the stable nodes.
  std::size_t deformed_inliers = 0;
  for (const auto i : inliers)
    deformed_inliers += li.deformed[static_cast<std::size_t>(i)];
  EXPECT_LT(deformed_inliers, 5u);
}

TEST(SacModelSurfaceMatching, RansacAndMsacRecoverTruthWith40PercentDeformed)
{
  const synth::LiSurface li = deformedSurface(40.0, 25.0, synth::DeformationPosition::LOWER_LEFT);
  const double sigma = 20.0;
  Model::Ptr model(new Model(li.mate, li.reference));
  ASSERT_TRUE(model->linearize(lhdStart(li)));
  pcl::RandomSampleConsensus<PointLiDAR> ransac(model, 3.0 * sigma);
  ransac.setMaxIterations(2000);
  ASSERT_TRUE(ransac.computeModel());
  Eigen::VectorXf c, refined;
  ransac.getModelCoefficients(c);
  ASSERT_TRUE(model->linearize(model->toMatrix(c)));  // second round, linearised there
  ASSERT_TRUE(ransac.computeModel());
  ransac.getModelCoefficients(c);
  pcl::Indices inliers;
  ransac.getInliers(inliers);
  EXPECT_GT(inliers.size(), 0.5 * li.mate->size());
  model->optimizeModelCoefficients(inliers, c, refined);
  EXPECT_LT(maxErrorSigma(model->toMatrix(refined), li, sigma), 0.5);

  ASSERT_TRUE(model->linearize(lhdStart(li)));
  pcl::MEstimatorSampleConsensus<PointLiDAR> msac(model, 3.0 * sigma);
  msac.setMaxIterations(2000);
  ASSERT_TRUE(msac.computeModel());
  msac.getModelCoefficients(c);
  ASSERT_TRUE(model->linearize(model->toMatrix(c)));
  ASSERT_TRUE(msac.computeModel());
  msac.getModelCoefficients(c);
  msac.getInliers(inliers);
  model->optimizeModelCoefficients(inliers, c, refined);
  EXPECT_LT(maxErrorSigma(model->toMatrix(refined), li, sigma), 0.5);
}

// Points without a conjugate (outside the reference) are never inliers and never break the
// median: their distance is +inf.
TEST(SacModelSurfaceMatching, UnmatchedPointsHaveInfiniteDistance)
{
  synth::LiSurface li = deformedSurface(0.0, 0.0, synth::DeformationPosition::MIDDLE);
  for (std::size_t i = 0; i < 100; ++i)
    (*li.mate)[i].x += 1e5f;  // far outside the reference
  (*li.mate)[200].z = std::numeric_limits<float>::quiet_NaN();
  Model model(li.mate, li.reference);
  ASSERT_TRUE(model.linearize(li.truth.matrix()));
  // Only observed points remain in the model's indices (PCL's median runs over them) ...
  const pcl::IndicesPtr observed = model.getIndices();
  EXPECT_EQ(observed->size(), model.getLinearization().size());
  EXPECT_LT(observed->size(), li.mate->size() - 100);
  EXPECT_TRUE(std::find(observed->begin(), observed->end(), 200) == observed->end());
  // ... and the distance of any other point is +inf.
  model.setIndices(pcl::Indices{0, 99, 200, 1275});
  std::vector<double> d;
  model.getDistancesToModel(model.toCoefficients(li.truth.matrix()), d);
  ASSERT_EQ(d.size(), 4u);
  EXPECT_TRUE(std::isinf(d[0]));
  EXPECT_TRUE(std::isinf(d[1]));
  EXPECT_TRUE(std::isinf(d[2]));
  EXPECT_TRUE(std::isfinite(d[3]));  // the middle of the grid
  pcl::Indices sample{0, 1275, 1276, 1277, 1325, 1375, 1425};
  Eigen::VectorXf c;
  EXPECT_FALSE(model.computeModelCoefficients(sample, c));
}
