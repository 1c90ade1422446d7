// PCL's own ICP registration tests (PCL 1.13.1 test/registration/test_registration.cpp) with
// pcl_ls3d::LeastSquaresSurfaceMatching swapped in for pcl::IterativeClosestPoint: only the class
// name changes (and the conjugate rule LND where PCL asks for point-to-plane), PCL's tolerances
// stay. Where PCL asserts its own ICP answer rather than a truth (bun0 -> bun4), the assertion
// is against the published ground truth instead (see IterativeClosestPoint below).
// Data: bun0.pcd / bun4.pcd from PCL_LS3D_SHARED_DATA_DIR/registration/pcl; the cases that need
// them skip with a message when the folder is absent.
#include <pcl_ls3d/registration/least_squares_surface_matching.h>

#include <pcl/common/io.h>
#include <pcl/common/transforms.h>
#include <pcl/features/normal_3d.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>
#include <pcl/registration/correspondence_estimation_normal_shooting.h>
#include <pcl/registration/correspondence_rejection_median_distance.h>
#include <pcl/registration/correspondence_rejection_sample_consensus.h>
#include <pcl/registration/correspondence_rejection_surface_normal.h>
#include <pcl/registration/transformation_estimation_point_to_plane.h>
#include <pcl/search/kdtree.h>

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

using namespace pcl;

namespace {

PointCloud<PointXYZ> cloud_source, cloud_target, cloud_reg;

// bun0.pcd and bun4.pcd as PCL's test main() loads them; false (with the reason) when absent.
bool
loadBunnies(std::string& why)
{
  static int state = 0;  // 0 not tried, 1 loaded, -1 absent
  static std::string reason;
  if (state == 0) {
    const std::filesystem::path dir =
        std::filesystem::path(PCL_LS3D_SHARED_DATA_DIR) / "registration" / "pcl";
    const auto bun0 = dir / "bun0.pcd", bun4 = dir / "bun4.pcd";
    if (!std::filesystem::exists(bun0) || !std::filesystem::exists(bun4)) {
      state = -1;
      reason = "PCL's bun0.pcd / bun4.pcd not found in " + dir.string() +
               " (configure with -DPCL_LS3D_SHARED_DATA_DIR=<shared data folder>); skipped";
    } else if (io::loadPCDFile(bun0.string(), cloud_source) < 0 ||
               io::loadPCDFile(bun4.string(), cloud_target) < 0) {
      state = -1;
      reason = "bun0.pcd / bun4.pcd in " + dir.string() + " could not be read; skipped";
    } else
      state = 1;
  }
  why = reason;
  return state == 1;
}

#define REQUIRE_BUNNIES()                                                                                    \
  do {                                                                                                       \
    std::string why_;                                                                                        \
    if (!loadBunnies(why_))                                                                                  \
      GTEST_SKIP() << why_;                                                                                  \
  } while (0)

// Published bun0 -> bun4 ground truth (PCL master, TEST PPFRegistration).
Eigen::Matrix4d
bun0ToBun4GroundTruth()
{
  Eigen::Matrix4d t;
  t << 0.825336, 0.000000, -0.564642, 0.037267,  //
      0.000000, 1.000000, 0.000000, 0.000000,    //
      0.564642, 0.000000, 0.825336, 0.038325,    //
      0.0, 0.0, 0.0, 1.0;
  return t;
}

// Rotation angle [deg] of a⁻¹ b (rotation parts re-orthonormalised: the published GT has 6
// digits).
double
angleBetweenDeg(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b)
{
  const Eigen::Quaterniond qa(Eigen::Matrix3d(a.topLeftCorner<3, 3>()));
  const Eigen::Quaterniond qb(Eigen::Matrix3d(b.topLeftCorner<3, 3>()));
  return qa.normalized().angularDistance(qb.normalized()) * 180.0 / M_PI;
}

// RMS of the point-to-plane distance of bun0 under `t` to bun4: the distance along the normal
// of the target point nearest each transformed source point, over the source
// points with that nearest point within `reach` (bun0 and bun4 overlap only partly).
double
pointToPlaneRms(const Eigen::Matrix4d& t, double reach)
{
  static PointCloud<PointNormal>::Ptr target;
  static search::KdTree<PointNormal> tree;
  if (!target) {  // bun4.pcd has no normals: PCA normals of 10 neighbours, as PCL's test does
    target.reset(new PointCloud<PointNormal>);
    copyPointCloud(cloud_target, *target);
    NormalEstimation<PointNormal, PointNormal> norm_est;
    norm_est.setSearchMethod(search::KdTree<PointNormal>::Ptr(new search::KdTree<PointNormal>));
    norm_est.setKSearch(10);
    norm_est.setInputCloud(target);
    norm_est.compute(*target);
    tree.setInputCloud(target);
  }
  double sum = 0.0;
  std::size_t n = 0;
  Indices nn;
  std::vector<float> d2;
  for (const auto& p : cloud_source) {
    const Eigen::Vector3d x = (t * Eigen::Vector4d(p.x, p.y, p.z, 1.0)).head<3>();
    PointNormal q;
    q.x = static_cast<float>(x.x());
    q.y = static_cast<float>(x.y());
    q.z = static_cast<float>(x.z());
    if (tree.nearestKSearch(q, 1, nn, d2) < 1 || d2[0] > reach * reach)
      continue;
    const PointNormal& m = (*target)[static_cast<std::size_t>(nn[0])];
    const double dist =
        m.getNormalVector3fMap().cast<double>().normalized().dot(x - m.getVector3fMap().cast<double>());
    sum += dist * dist;
    ++n;
  }
  return n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

}  // namespace

//////////////////////////////////////////////////////////////////////////////////////////////
// PCL: "This test if the ICP algorithm can successfully find the transformation of a cloud that
// has been moved 0.7 in x direction." Five random points in a 1024 cube: far too few for a local
// surface, so LS3D falls back to point-to-point observations (three per point).
TEST(PclDropin, ICP_translated)
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud_in(new pcl::PointCloud<pcl::PointXYZ>(5, 1));
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud_out(new pcl::PointCloud<pcl::PointXYZ>);

  // Fill in the CloudIn data
  for (auto& point : *cloud_in) {
    // PCL's test writes 1024 * rand() / ..., an int overflow (UB) the sanitizer build reports.
    point.x = 1024 * (rand() / (RAND_MAX + 1.0f));
    point.y = 1024 * (rand() / (RAND_MAX + 1.0f));
    point.z = 1024 * (rand() / (RAND_MAX + 1.0f));
  }

  *cloud_out = *cloud_in;

  for (auto& point : *cloud_out)
    point.x += 0.7f;

  pcl_ls3d::LeastSquaresSurfaceMatching<pcl::PointXYZ, pcl::PointXYZ> icp;
  icp.setInputSource(cloud_in);
  icp.setInputTarget(cloud_out);

  pcl::PointCloud<pcl::PointXYZ> Final;
  icp.align(Final);

  // Check that we have successfully converged
  ASSERT_TRUE(icp.hasConverged());

  // Test that the fitness score is below acceptable threshold
  EXPECT_LT(icp.getFitnessScore(), 1e-6);

  // Ensure that the translation found is within acceptable threshold.
  EXPECT_NEAR(icp.getFinalTransformation()(0, 3), 0.7, 2e-3);
  EXPECT_NEAR(icp.getFinalTransformation()(1, 3), 0.0, 2e-3);
  EXPECT_NEAR(icp.getFinalTransformation()(2, 3), 0.0, 2e-3);
}

//////////////////////////////////////////////////////////////////////////////////////////////
// bun0 -> bun4 from the identity (a 34° rotation). PCL asserts its own ICP result to 1e-3
// (R(0,0) = 0.8806, i.e. 28.3° about y), which is ~6.6° from the published ground truth: that is
// an answer, not a truth, so this port asserts against the ground truth instead. The ground
// truth is itself not exact (6 digits, and its point-to-plane fit is worse than LS3D's: RMS
// 1.23 mm at the GT against 0.73 mm at the LS3D estimate), so the honest assertions are a bound
// relative to the GT (angle < 1.5°, translation < 5 mm; LS3D lands ~1° / ~2 mm off it) plus
// "fits the data better than the GT does".
template <typename Scalar>
void
runBun0ToBun4()
{
  pcl_ls3d::LeastSquaresSurfaceMatching<PointXYZ, PointXYZ, Scalar> reg;
  PointCloud<PointXYZ>::ConstPtr source(cloud_source.makeShared());
  reg.setInputSource(source);
  reg.setInputTarget(cloud_target.makeShared());
  reg.setMaximumIterations(50);
  reg.setTransformationEpsilon(1e-8);
  reg.setMaxCorrespondenceDistance(0.05);

  // Register
  PointCloud<PointXYZ> out;
  reg.align(out);
  EXPECT_EQ(out.size(), cloud_source.size());
  ASSERT_TRUE(reg.hasConverged()) << pcl_ls3d::terminationTypeToString(reg.getReport().termination) << ": "
                                  << reg.getReport().message;

  const Eigen::Matrix4d transformation = reg.getFinalTransformation().template cast<double>();
  const Eigen::Matrix4d gt = bun0ToBun4GroundTruth();
  const double angle = angleBetweenDeg(transformation, gt);
  const double shift = (transformation.topRightCorner<3, 1>() - gt.topRightCorner<3, 1>()).norm();
  EXPECT_LT(angle, 1.5);
  EXPECT_LT(shift, 5e-3);
  for (double r : {0.002, 0.003, 0.005, 0.01})
    std::printf("reach %.3f: est %.3f mm gt %.3f mm\n", r, 1e3 * pointToPlaneRms(transformation, r),
                1e3 * pointToPlaneRms(gt, r));
  const double rms_estimate = pointToPlaneRms(transformation, 0.005);
  const double rms_gt = pointToPlaneRms(gt, 0.005);
  EXPECT_LT(rms_estimate, rms_gt);
  std::printf("bun0->bun4: %.3f deg / %.2f mm from the GT; point-to-plane RMS %.3f mm "
              "(GT %.3f mm)\n",
              angle, 1e3 * shift, 1e3 * rms_estimate, 1e3 * rms_gt);

  EXPECT_EQ(transformation(3, 0), 0);
  EXPECT_EQ(transformation(3, 1), 0);
  EXPECT_EQ(transformation(3, 2), 0);
  EXPECT_EQ(transformation(3, 3), 1);
}

TEST(PclDropin, IterativeClosestPoint)
{
  REQUIRE_BUNNIES();
  runBun0ToBun4<float>();
}

// The same with Scalar = double (PCL's IterativeClosestPointWithNormals only checks a setter of
// its double instantiation).
TEST(PclDropin, IterativeClosestPointDouble)
{
  REQUIRE_BUNNIES();
  runBun0ToBun4<double>();
}

//////////////////////////////////////////////////////////////////////////////////////////////
// PCL's bun0 -> bun4 case with every conjugate rule (PCL's settings: 50 iterations, epsilon
// 1e-8, 5 cm correspondences, rigid). LND and ICP land within 1.5° / 5 mm of the ground truth
// (before the fix of step_extrapolation.h the ICP rule ended CONVERGED 52° away: its approach
// steps of 8.7° were extrapolated ten-fold into another minimum). LZD measures vertical
// differences, no surface distance on a closed object: the quality gate refuses it (σ0 above
// 3 x the surfaces' noise), and hasConverged() says so.
TEST(PclDropin, IterativeClosestPointEveryRule)
{
  REQUIRE_BUNNIES();
  for (const auto rule : {pcl_ls3d::ConjugateRuleType::LND, pcl_ls3d::ConjugateRuleType::LZD,
                          pcl_ls3d::ConjugateRuleType::ICP}) {
    pcl_ls3d::LeastSquaresSurfaceMatching<PointXYZ, PointXYZ> reg;
    reg.setConjugateRule(rule);
    reg.setInputSource(cloud_source.makeShared());
    reg.setInputTarget(cloud_target.makeShared());
    reg.setMaximumIterations(50);
    reg.setTransformationEpsilon(1e-8);
    reg.setMaxCorrespondenceDistance(0.05);
    PointCloud<PointXYZ> out;
    reg.align(out);
    const auto& report = reg.getReport();
    const Eigen::Matrix4d t = reg.getFinalTransformation().cast<double>();
    const double angle = angleBetweenDeg(t, bun0ToBun4GroundTruth());
    const double shift = (t.topRightCorner<3, 1>() - bun0ToBun4GroundTruth().topRightCorner<3, 1>()).norm();
    std::printf("%s: %s, %.2f deg / %.1f mm from the GT\n", report.rule_name.c_str(),
                pcl_ls3d::terminationTypeToString(report.termination), angle, 1e3 * shift);
    if (rule == pcl_ls3d::ConjugateRuleType::LZD) {
      EXPECT_FALSE(reg.hasConverged());
      EXPECT_EQ(report.termination, pcl_ls3d::TerminationType::UNRELIABLE) << report.message;
      continue;
    }
    ASSERT_TRUE(reg.hasConverged()) << report.rule_name << ": " << report.message;
    EXPECT_LT(angle, 1.5) << report.rule_name;
    EXPECT_LT(shift, 5e-3) << report.rule_name;
  }
}

// Started in the minimum the ICP rule used to end in (52° from the truth; the 4x4 it returned
// on main 0a2f88a, rounded to 6 digits), no rule may call the result converged. LND and LZD
// leave it with σ0 3.6 and 5.3 x the surfaces' noise; the ICP rule stays there with σ0 only
// 1.9 x, because its two tangential observations per point (weighted to the normal's variance,
// carrying the closest point's sampling offset) dilute the misfit: the gate judges its
// residuals across the surface, 3.2 x the noise (0.33 x at the right fit).
TEST(PclDropin, WrongMinimumIsRefusedByEveryRule)
{
  REQUIRE_BUNNIES();
  Eigen::Matrix4f wrong;
  wrong << 0.549456f, 0.799146f, -0.243851f, -0.026069f,  //
      -0.593247f, 0.578661f, 0.559651f, 0.033988f,        //
      0.588350f, -0.162840f, 0.792040f, 0.049487f,        //
      0.0f, 0.0f, 0.0f, 1.0f;
  ASSERT_GT(angleBetweenDeg(wrong.cast<double>(), bun0ToBun4GroundTruth()), 45.0);
  for (const auto rule : {pcl_ls3d::ConjugateRuleType::LND, pcl_ls3d::ConjugateRuleType::LZD,
                          pcl_ls3d::ConjugateRuleType::ICP}) {
    pcl_ls3d::LeastSquaresSurfaceMatching<PointXYZ, PointXYZ> reg;
    reg.setConjugateRule(rule);
    reg.setInputSource(cloud_source.makeShared());
    reg.setInputTarget(cloud_target.makeShared());
    reg.setMaximumIterations(50);
    reg.setTransformationEpsilon(1e-8);
    reg.setMaxCorrespondenceDistance(0.05);
    PointCloud<PointXYZ> out;
    reg.align(out, wrong);
    const auto& report = reg.getReport();
    const double angle =
        angleBetweenDeg(reg.getFinalTransformation().cast<double>(), bun0ToBun4GroundTruth());
    std::printf("%s from the wrong minimum: %s, %.1f deg from the GT: %s\n", report.rule_name.c_str(),
                pcl_ls3d::terminationTypeToString(report.termination), angle, report.message.c_str());
    ASSERT_GT(angle, 20.0) << report.rule_name << " left the wrong minimum: the case is void";
    EXPECT_FALSE(reg.hasConverged()) << report.rule_name;
    // UNRELIABLE, or STALLED when the estimate stayed at the guess (the ICP rule).
    EXPECT_TRUE(report.termination == pcl_ls3d::TerminationType::UNRELIABLE ||
                report.termination == pcl_ls3d::TerminationType::STALLED)
        << report.rule_name << ": " << pcl_ls3d::terminationTypeToString(report.termination);
    EXPECT_TRUE(report.hasEstimate()) << report.rule_name;  // refused, but readable
  }
}

//////////////////////////////////////////////////////////////////////////////////////////////
void
sampleRandomTransform(Eigen::Affine3f& trans, float max_angle, float max_trans)
{
  srand(0);
  // Sample random transform
  Eigen::Vector3f axis(static_cast<float>(rand()) / RAND_MAX, static_cast<float>(rand()) / RAND_MAX,
                       static_cast<float>(rand()) / RAND_MAX);
  axis.normalize();
  float angle = static_cast<float>(rand()) / RAND_MAX * max_angle;
  Eigen::Vector3f translation(static_cast<float>(rand()) / RAND_MAX, static_cast<float>(rand()) / RAND_MAX,
                              static_cast<float>(rand()) / RAND_MAX);
  translation *= max_trans;
  Eigen::Affine3f rotation(Eigen::AngleAxis<float>(angle, axis));
  trans = Eigen::Translation3f(translation) * rotation;
}

// PCL's rejector case: a median-distance and a sample-consensus rejector added with
// addCorrespondenceRejector filter LS3D's observations every iteration.
// Source and target are the same 397 points 10 m from the origin, so PCL's 1 cm translation
// tolerance allows ~1e-3 rad of rotation: LND reaches the exact answer (4e-7 m) because near a
// target sample its local surface passes through that sample (tin_rules.cpp). Note that PCL's
// sampleRandomTransform() re-seeds with srand(0), so its ten "random" cases are one case.
TEST(PclDropin, IterativeClosestPointWithRejectors)
{
  REQUIRE_BUNNIES();
  pcl_ls3d::LeastSquaresSurfaceMatching<PointXYZ, PointXYZ> reg;
  reg.setMaximumIterations(50);
  reg.setTransformationEpsilon(1e-8);
  reg.setMaxCorrespondenceDistance(0.15);
  // Add a median distance rejector
  pcl::registration::CorrespondenceRejectorMedianDistance::Ptr rej_med(
      new pcl::registration::CorrespondenceRejectorMedianDistance);
  rej_med->setMedianFactor(4.0);
  reg.addCorrespondenceRejector(rej_med);
  // Also add a SaC rejector
  pcl::registration::CorrespondenceRejectorSampleConsensus<PointXYZ>::Ptr rej_samp(
      new pcl::registration::CorrespondenceRejectorSampleConsensus<PointXYZ>);
  reg.addCorrespondenceRejector(rej_samp);

  std::size_t ntransforms = 10;
  for (std::size_t t = 0; t < ntransforms; t++) {
    // Sample a fixed offset between cloud pairs
    Eigen::Affine3f delta_transform;
    sampleRandomTransform(delta_transform, 0., 0.05);
    // Sample random global transform for each pair, to make sure we aren't biased around the
    // origin
    Eigen::Affine3f net_transform;
    sampleRandomTransform(net_transform, 2 * M_PI, 10.);

    PointCloud<PointXYZ>::ConstPtr source(cloud_source.makeShared());
    PointCloud<PointXYZ>::Ptr source_trans(new PointCloud<PointXYZ>);
    PointCloud<PointXYZ>::Ptr target_trans(new PointCloud<PointXYZ>);

    pcl::transformPointCloud(*source, *source_trans, delta_transform.inverse() * net_transform);
    pcl::transformPointCloud(*source, *target_trans, net_transform);

    reg.setInputSource(source_trans);
    reg.setInputTarget(target_trans);

    // Register
    reg.align(cloud_reg);
    Eigen::Matrix4f trans_final = reg.getFinalTransformation();
    // Translation should be within 1cm
    for (int y = 0; y < 4; y++)
      EXPECT_NEAR(trans_final(y, 3), delta_transform(y, 3), 1E-2);
    // Rotation within .1
    for (int y = 0; y < 4; y++)
      for (int x = 0; x < 3; x++)
        EXPECT_NEAR(trans_final(y, x), delta_transform(y, x), 1E-1);
  }
}

//////////////////////////////////////////////////////////////////////////////////////////////
TEST(PclDropin, IterativeClosestPointNonLinear)
{
  REQUIRE_BUNNIES();
  using PointT = PointXYZRGB;
  PointCloud<PointT>::Ptr temp_src(new PointCloud<PointT>);
  copyPointCloud(cloud_source, *temp_src);
  PointCloud<PointT>::Ptr temp_tgt(new PointCloud<PointT>);
  copyPointCloud(cloud_target, *temp_tgt);
  PointCloud<PointT> output;

  pcl_ls3d::LeastSquaresSurfaceMatching<PointT, PointT> reg;
  reg.setInputSource(temp_src);
  reg.setInputTarget(temp_tgt);
  reg.setMaximumIterations(50);
  reg.setTransformationEpsilon(1e-8);

  // Register
  reg.align(output);
  EXPECT_EQ(output.size(), cloud_source.size());
  EXPECT_LT(reg.getFitnessScore(), 0.001);

  // Check again, for all possible caching schemes
  for (int iter = 0; iter < 4; iter++) {
    bool force_cache = static_cast<bool>(iter / 2);
    bool force_cache_reciprocal = static_cast<bool>(iter % 2);
    pcl::search::KdTree<PointT>::Ptr tree(new pcl::search::KdTree<PointT>);
    // Ensure that, when force_cache is not set, we are robust to the wrong input
    if (force_cache)
      tree->setInputCloud(temp_tgt);
    reg.setSearchMethodTarget(tree, force_cache);

    pcl::search::KdTree<PointT>::Ptr tree_recip(new pcl::search::KdTree<PointT>);
    if (force_cache_reciprocal)
      tree_recip->setInputCloud(temp_src);
    reg.setSearchMethodSource(tree_recip, force_cache_reciprocal);

    // Register
    reg.align(output);
    EXPECT_EQ(output.size(), cloud_source.size());
    EXPECT_LT(reg.getFitnessScore(), 0.001);
  }
}

//////////////////////////////////////////////////////////////////////////////////////////////
// PCL's point-to-plane case. LS3D ignores setTransformationEstimation and
// setCorrespondenceEstimation (it warns once): its conjugate rule LND is the point-to-plane
// counterpart and is set explicitly. The surface-normal rejector is honoured like ICP honours
// it; note that the source here has zero normals (copyPointCloud from PointXYZ), so that
// rejector (score n_s·n_t > 0) rejects every correspondence, in PCL's ICP as in LS3D: PCL's
// fitness check then passes at the identity. The ported assertions are kept as they are; the
// LND variant without the rejector below shows the registration itself.
TEST(PclDropin, IterativeClosestPoint_PointToPlane)
{
  REQUIRE_BUNNIES();
  using PointT = PointNormal;
  PointCloud<PointT>::Ptr src(new PointCloud<PointT>);
  copyPointCloud(cloud_source, *src);
  PointCloud<PointT>::Ptr tgt(new PointCloud<PointT>);
  copyPointCloud(cloud_target, *tgt);
  PointCloud<PointT> output;

  NormalEstimation<PointNormal, PointNormal> norm_est;
  norm_est.setSearchMethod(search::KdTree<PointNormal>::Ptr(new search::KdTree<PointNormal>));
  norm_est.setKSearch(10);
  norm_est.setInputCloud(tgt);
  norm_est.compute(*tgt);

  pcl_ls3d::LeastSquaresSurfaceMatching<PointT, PointT> reg;
  reg.setConjugateRule(pcl_ls3d::ConjugateRuleType::LND);
  using PointToPlane = registration::TransformationEstimationPointToPlane<PointT, PointT>;
  PointToPlane::Ptr point_to_plane(new PointToPlane);
  reg.setTransformationEstimation(point_to_plane);
  reg.setInputSource(src);
  reg.setInputTarget(tgt);
  reg.setMaximumIterations(50);
  reg.setTransformationEpsilon(1e-8);
  // Use a correspondence estimator which needs normals
  registration::CorrespondenceEstimationNormalShooting<PointT, PointT, PointT>::Ptr ce(
      new registration::CorrespondenceEstimationNormalShooting<PointT, PointT, PointT>);
  reg.setCorrespondenceEstimation(ce);
  // Add rejector
  registration::CorrespondenceRejectorSurfaceNormal::Ptr rej(
      new registration::CorrespondenceRejectorSurfaceNormal);
  rej->setThreshold(0);  // Could be a lot of rotation -- just make sure they're at least within 0 degrees
  reg.addCorrespondenceRejector(rej);

  // Register
  reg.align(output);
  EXPECT_EQ(output.size(), cloud_source.size());
  EXPECT_LT(reg.getFitnessScore(), 0.005);

  // Check again, for all possible caching schemes
  for (int iter = 0; iter < 4; iter++) {
    bool force_cache = static_cast<bool>(iter / 2);
    bool force_cache_reciprocal = static_cast<bool>(iter % 2);
    pcl::search::KdTree<PointT>::Ptr tree(new pcl::search::KdTree<PointT>);
    // Ensure that, when force_cache is not set, we are robust to the wrong input
    if (force_cache)
      tree->setInputCloud(tgt);
    reg.setSearchMethodTarget(tree, force_cache);

    pcl::search::KdTree<PointT>::Ptr tree_recip(new pcl::search::KdTree<PointT>);
    if (force_cache_reciprocal)
      tree_recip->setInputCloud(src);
    reg.setSearchMethodSource(tree_recip, force_cache_reciprocal);

    // Register
    reg.align(output);
    EXPECT_EQ(output.size(), cloud_source.size());
    EXPECT_LT(reg.getFitnessScore(), 0.005);
  }
}

// Not in PCL: the point-to-plane case without the all-rejecting normal rejector, asserted on
// convergence and against the ground truth (PointNormal instantiation, normals in the output
// rotated like ICP's transformCloud does).
TEST(PclDropin, PointToPlaneLndAgainstGroundTruth)
{
  REQUIRE_BUNNIES();
  using PointT = PointNormal;
  PointCloud<PointT>::Ptr src(new PointCloud<PointT>);
  copyPointCloud(cloud_source, *src);
  PointCloud<PointT>::Ptr tgt(new PointCloud<PointT>);
  copyPointCloud(cloud_target, *tgt);
  for (auto& p : *src) {
    p.normal_x = 0.0f;
    p.normal_y = 0.0f;
    p.normal_z = 1.0f;
  }
  pcl_ls3d::LeastSquaresSurfaceMatching<PointT, PointT> reg;
  reg.setConjugateRule(pcl_ls3d::ConjugateRuleType::LND);
  reg.setInputSource(src);
  reg.setInputTarget(tgt);
  reg.setMaximumIterations(50);
  reg.setTransformationEpsilon(1e-8);
  PointCloud<PointT> output;
  reg.align(output);
  ASSERT_TRUE(reg.hasConverged()) << reg.getReport().message;
  const Eigen::Matrix4d t = reg.getFinalTransformation().cast<double>();
  EXPECT_LT(angleBetweenDeg(t, bun0ToBun4GroundTruth()), 1.5);
  EXPECT_LT(reg.getFitnessScore(), 0.005);
  const Eigen::Vector3d n = t.topLeftCorner<3, 3>().col(2);
  EXPECT_NEAR(output[0].normal_x, n.x(), 1e-5);
  EXPECT_NEAR(output[0].normal_z, n.z(), 1e-5);
}

//////////////////////////////////////////////////////////////////////////////////////////////
// Not in PCL's file but in its tutorial's spirit: the bunny moved by 0.2 m in z (more than its
// own size, so no source point lies over the target's box under the identity) must be
// registered, not refused as NO_OVERLAP: with the default unlimited correspondence distance
// every point may find a correspondence, as in ICP.
TEST(PclDropin, ShiftedBeyondItsSizeIsNotRefused)
{
  REQUIRE_BUNNIES();
  PointCloud<PointXYZ>::Ptr src(new PointCloud<PointXYZ>(cloud_source));
  PointCloud<PointXYZ>::Ptr tgt(new PointCloud<PointXYZ>(cloud_source));
  for (auto& p : *tgt)
    p.z += 0.2f;
  pcl_ls3d::LeastSquaresSurfaceMatching<PointXYZ, PointXYZ> reg;
  reg.setInputSource(src);
  reg.setInputTarget(tgt);
  PointCloud<PointXYZ> out;
  reg.align(out);
  EXPECT_NE(reg.getReport().termination, pcl_ls3d::TerminationType::NO_OVERLAP);
  ASSERT_TRUE(reg.hasConverged()) << pcl_ls3d::terminationTypeToString(reg.getReport().termination) << ": "
                                  << reg.getReport().message;
  const Eigen::Matrix4f t = reg.getFinalTransformation();
  std::printf("0.2 m shift: t = (%.6f, %.6f, %.6f)\n", t(0, 3), t(1, 3), t(2, 3));
  EXPECT_NEAR(t(2, 3), 0.2, 1e-3);
  EXPECT_NEAR(t(0, 3), 0.0, 1e-3);
  EXPECT_NEAR(t(1, 3), 0.0, 1e-3);
  // An exact copy: with the snap towards the nearest target sample nothing biases the rotation
  // (0.32° before it, the self-registration bias of issue 10 point 5).
  const double angle_deg = angleBetweenDeg(t.cast<double>(), Eigen::Matrix4d::Identity());
  std::printf("0.2 m shift: rotation left %.2e deg\n", angle_deg);
  EXPECT_LT(angle_deg, 0.01);
}

// The exact answer given as the initial guess stays: bun0 onto a rigidly moved copy of itself
// (30° about an oblique axis, 1 m away), guess = truth.
TEST(PclDropin, ExactGuessStays)
{
  REQUIRE_BUNNIES();
  const Eigen::Affine3f truth = Eigen::Translation3f(0.4f, -0.7f, 0.6f) *
                                Eigen::AngleAxisf(0.52f, Eigen::Vector3f(0.3f, 0.8f, -0.5f).normalized());
  PointCloud<PointXYZ>::Ptr src(new PointCloud<PointXYZ>(cloud_source));
  PointCloud<PointXYZ>::Ptr tgt(new PointCloud<PointXYZ>);
  pcl::transformPointCloud(cloud_source, *tgt, truth);
  pcl_ls3d::LeastSquaresSurfaceMatching<PointXYZ, PointXYZ> reg;
  reg.setInputSource(src);
  reg.setInputTarget(tgt);
  PointCloud<PointXYZ> out;
  reg.align(out, truth.matrix());
  ASSERT_TRUE(reg.hasConverged()) << pcl_ls3d::terminationTypeToString(reg.getReport().termination) << ": "
                                  << reg.getReport().message;
  const Eigen::Matrix4d t = reg.getFinalTransformation().cast<double>();
  const double angle = angleBetweenDeg(t, truth.matrix().cast<double>());
  const double shift =
      (t.topRightCorner<3, 1>() - truth.matrix().cast<double>().topRightCorner<3, 1>()).norm();
  std::printf("exact guess: moved %.2e deg, %.2e m\n", angle, shift);
  EXPECT_LT(angle, 1e-3);
  EXPECT_LT(shift, 1e-5);
}
