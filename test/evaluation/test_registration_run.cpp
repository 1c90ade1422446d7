// The method-independent evaluation of a run (uniform NN RMS, truth errors) and the PCL runner's
// refusal of empty input, against hand-computed values on a unit grid.
#include <pcl_ls3d/evaluation/ls3d_method.h>
#include <pcl_ls3d/evaluation/pcl_methods.h>
#include <pcl_ls3d/evaluation/registration_run.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_ls3d::evaluation;

namespace {
/// 21 × 21 points on the plane z = 0 with 1 m spacing.
pcl::PointCloud<pcl::PointXYZ>::Ptr
grid()
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr c(new pcl::PointCloud<pcl::PointXYZ>);
  for (int i = -10; i <= 10; ++i)
    for (int j = -10; j <= 10; ++j)
      c->push_back(pcl::PointXYZ(static_cast<float>(i), static_cast<float>(j), 0.f));
  return c;
}
}  // namespace

// Source = target: RMS 0 at the identity. Lifting by 0.1 m: every nearest neighbour is the point
// straight below (the next one is √(1 + 0.01) m away), so RMS = 0.1 (float coordinates: 1e-6).
// A 0.05 m cut-off then excludes every point (RMS undefined = NaN).
TEST(RegistrationRun, UniformRmsOnGrid)
{
  const auto cloud = grid();
  RunEvaluation eval(cloud, cloud, 1.0);
  RegistrationRun run;
  eval.evaluate(run, nullptr);
  EXPECT_EQ(run.rms_points, cloud->size());
  EXPECT_NEAR(run.rms, 0.0, 1e-9);
  EXPECT_FALSE(run.error.valid);  // no truth given

  run.transformation(2, 3) = 0.1;
  eval.evaluate(run, nullptr);
  EXPECT_EQ(run.rms_points, cloud->size());
  EXPECT_NEAR(run.rms, 0.1, 1e-6);

  RunEvaluation strict(cloud, cloud, 0.05);
  strict.evaluate(run, nullptr);
  EXPECT_EQ(run.rms_points, 0u);
  EXPECT_TRUE(std::isnan(run.rms));
}

// With a truth the displacement errors are filled: a 0.1 m lift against the identity truth is a
// 0.1 m error everywhere.
TEST(RegistrationRun, TruthErrorsFilled)
{
  const auto cloud = grid();
  RunEvaluation eval(cloud, cloud, 1.0);
  RegistrationRun run;
  run.transformation(2, 3) = 0.1;
  const Eigen::Matrix4d truth = Eigen::Matrix4d::Identity();
  eval.evaluate(run, &truth);
  ASSERT_TRUE(run.error.valid);
  EXPECT_EQ(run.error.points, cloud->size());
  EXPECT_NEAR(run.error.mean, 0.1, 1e-12);
  EXPECT_NEAR(run.error.max_bbox, 0.1, 1e-12);
  EXPECT_NEAR(run.error.parameters[pcl_ls3d::TZ], 0.1, 1e-12);
}

// Empty input is refused with a message, never a crash, by every runner.
TEST(RegistrationRun, EmptyInputRefused)
{
  const auto cloud = grid();
  const pcl::PointCloud<pcl::PointXYZ>::Ptr empty(new pcl::PointCloud<pcl::PointXYZ>);
  for (auto m : allPclMethods()) {
    const auto run = runPclMethod(m, empty, cloud);
    EXPECT_FALSE(run.ran) << pclMethodName(m);
    EXPECT_FALSE(run.message.empty());
  }
  const auto run = runLs3d(pcl_ls3d::ConjugateRuleType::LND, cloud, empty);
  EXPECT_FALSE(run.ran);
  EXPECT_EQ(run.name, "LS3D-LND");
}

// Point-to-point ICP recovers a pure 0.2 m vertical shift of a grid exactly (every nearest
// neighbour is the point's own copy): checks that the runner returns PCL's transform, iterations
// and convergence flag.
TEST(RegistrationRun, PclIcpRecoversVerticalShift)
{
  const auto target = grid();
  pcl::PointCloud<pcl::PointXYZ>::Ptr source(new pcl::PointCloud<pcl::PointXYZ>(*target));
  for (auto& p : *source)
    p.z -= 0.2f;
  const auto run = runPclMethod(PclMethod::ICP, source, target);
  ASSERT_TRUE(run.ran) << run.message;
  EXPECT_TRUE(run.converged);
  EXPECT_GT(run.iterations, 0);
  EXPECT_NEAR(run.transformation(2, 3), 0.2, 1e-5);  // float ICP on unit-sized data
  EXPECT_GT(run.time_s, 0.0);
}
