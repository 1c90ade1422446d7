// HeightUnits against an independent computation: points moved in metres and expressed in
// files whose heights are in feet (or metres), on each side of a transformation.
#include <pcl_ls3d/common/height_units.h>
#include <pcl_ls3d/common/similarity_transform.h>

#include <pcl/point_types.h>

#include <gtest/gtest.h>

namespace {

constexpr double kUsFoot = 1200.0 / 3937.0;  // metres per US survey foot

pcl_ls3d::SimilarityTransform
tilted()
{
  pcl_ls3d::SimilarityTransform T;
  T.t = Eigen::Vector3d(0.5, -0.3, 0.2);
  T.phi = 0.02;
  T.omega = -0.015;
  T.kappa = 0.03;
  T.m = 1.0002;
  return T;
}

}  // namespace

// toFiles maps a source point as its file stores it to where the target's file stores the
// moved point; toWorking undoes it.
TEST(HeightUnits, TransformationsBetweenFilesOfDifferentUnits)
{
  const pcl_ls3d::HeightUnits h{1.0, kUsFoot};  // target in metres, source in feet
  const pcl_ls3d::SimilarityTransform T = tilted();
  const Eigen::Matrix4d files = h.toFiles(T.matrix());
  for (const Eigen::Vector3d& metres :
       {Eigen::Vector3d(10.0, -20.0, 105.0), Eigen::Vector3d(-300.0, 40.0, 2.5)}) {
    const Eigen::Vector3d source_file(metres.x(), metres.y(), metres.z() / kUsFoot);
    const Eigen::Vector3d expected = T.apply(metres);  // target in metres: as is
    EXPECT_LT(((files * source_file.homogeneous()).head<3>() - expected).norm(), 1e-9);
  }
  EXPECT_LT((h.toWorking(files) - T.matrix()).norm(), 1e-12);
  const pcl_ls3d::HeightUnits same = pcl_ls3d::HeightUnits::ofOneFile(kUsFoot);
  EXPECT_TRUE(same.converts());
  EXPECT_FALSE(pcl_ls3d::HeightUnits{}.converts());
  EXPECT_EQ(pcl_ls3d::HeightUnits{}.toFiles(T.matrix()), T.matrix());
}

// pairToWorking gives each point its height in the plan unit around the working origin, also
// for a source whose factor differs from the target's; heightsToFile brings the files' values
// back.
TEST(HeightUnits, PairToWorkingAndBack)
{
  const pcl_ls3d::HeightUnits h{kUsFoot, 1.0};                    // target in feet, source in metres
  const Eigen::Vector3d file_origin(500000.0, 5000000.0, 300.0);  // in the target's feet
  pcl::PointCloud<pcl::PointXYZ> target, source;
  target.push_back(pcl::PointXYZ(1.0f, 2.0f, 28.0f));    // file height 328 ft
  source.push_back(pcl::PointXYZ(3.0f, 4.0f, -199.0f));  // file height 101 m
  const pcl::PointCloud<pcl::PointXYZ> target_in = target, source_in = source;
  const Eigen::Vector3d working_origin = pcl_ls3d::pairToWorking(h, file_origin, target, source);
  EXPECT_NEAR(working_origin.z(), 300.0 * kUsFoot, 1e-9);
  EXPECT_NEAR(target[0].z + working_origin.z(), 328.0 * kUsFoot, 1e-4);
  EXPECT_NEAR(source[0].z + working_origin.z(), 101.0, 1e-4);
  EXPECT_EQ(target[0].x, target_in[0].x);
  pcl_ls3d::heightsToFile(target, h.target, h.target, file_origin.z());
  pcl_ls3d::heightsToFile(source, h.source, h.target, file_origin.z());
  EXPECT_NEAR(target[0].z, target_in[0].z, 1e-4);
  EXPECT_NEAR(source[0].z, source_in[0].z, 1e-4);
  EXPECT_NEAR(h.sourceToFile(Eigen::Vector3d(0, 0, 101.0)).z(), 101.0, 1e-12);
  EXPECT_NEAR(h.targetToWorking(file_origin).z(), working_origin.z(), 1e-12);
}
