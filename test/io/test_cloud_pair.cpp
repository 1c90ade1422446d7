// cloud_pair.h: a pair loaded the one way the pair tools load it. The source lands in the
// target's local origin (checked against the written global coordinates), an input in degrees
// is refused with one line naming it, and a missing file is named.
#include "io/io_test_utils.h"

#include <pcl_ls3d/io/cloud_pair.h>
#include <pcl_ls3d/maps/coordinate_reference.h>

#include <gtest/gtest.h>

using namespace pcl_ls3d;

namespace {

pcl::PointCloud<PointLiDAR>
grid(float step, int n)
{
  pcl::PointCloud<PointLiDAR> c;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      PointLiDAR p;
      p.x = step * static_cast<float>(i);
      p.y = step * static_cast<float>(j);
      p.z = 0.25f * static_cast<float>(i % 3);
      c.push_back(p);
    }
  return c;
}

TEST(CloudPair, SourceLandsInTheTargetsOrigin)
{
  const pcl_ls3d_test::TempDir dir("ls3d_cloud_pair");
  const Eigen::Vector3d target_origin(500000.0, 5000000.0, 100.0), source_origin(500040.0, 4999990.0, 90.0);
  std::string error;
  const pcl::PointCloud<PointLiDAR> target = grid(1.0f, 10), source = grid(2.0f, 5);
  ASSERT_TRUE(io::saveCloud(dir.file("target.pcd"), target, target_origin, error)) << error;
  ASSERT_TRUE(io::saveCloud(dir.file("source.pcd"), source, source_origin, error)) << error;

  io::CloudPair pair;
  ASSERT_TRUE(io::loadCloudPair(dir.file("target.pcd"), dir.file("source.pcd"), pair, error)) << error;
  ASSERT_EQ(pair.target->size(), target.size());
  ASSERT_EQ(pair.source->size(), source.size());
  EXPECT_FALSE(pair.heights.converts());
  EXPECT_TRUE(pair.working_origin.isApprox(pair.target_info.origin, 1e-12));  // no height converted
  EXPECT_TRUE(pair.warnings.empty() && pair.notes.empty());
  // Both clouds around the one origin the target was loaded with.
  for (std::size_t i = 0; i < source.size(); ++i) {
    const Eigen::Vector3d global = source_origin + source[i].getVector3fMap().cast<double>();
    const Eigen::Vector3d loaded =
        pair.target_info.origin + (*pair.source)[i].getVector3fMap().cast<double>();
    EXPECT_LT((loaded - global).norm(), 1e-4) << "point " << i;
  }
  for (std::size_t i = 0; i < target.size(); ++i) {
    const Eigen::Vector3d global = target_origin + target[i].getVector3fMap().cast<double>();
    const Eigen::Vector3d loaded =
        pair.target_info.origin + (*pair.target)[i].getVector3fMap().cast<double>();
    EXPECT_LT((loaded - global).norm(), 1e-4) << "point " << i;
  }
}

TEST(CloudPair, DegreesAndMissingFilesAreRefused)
{
  const pcl_ls3d_test::TempDir dir("ls3d_cloud_pair_bad");
  std::string error;
  ASSERT_TRUE(io::saveCloud(dir.file("plain.pcd"), grid(1.0f, 5), Eigen::Vector3d::Zero(), error)) << error;
  io::SaveOptions in_degrees;
  in_degrees.crs_wkt = maps::crsFromUserInput("EPSG:4326", &error);
  ASSERT_FALSE(in_degrees.crs_wkt.empty()) << error;
  ASSERT_TRUE(io::saveCloud(dir.file("degrees.pcd"), grid(1e-5f, 5), Eigen::Vector3d(2.0, 48.0, 0.0), error,
                            in_degrees))
      << error;

  io::CloudPair pair;
  error.clear();
  EXPECT_FALSE(io::loadCloudPair(dir.file("plain.pcd"), dir.file("degrees.pcd"), pair, error));
  EXPECT_NE(error.find("degrees.pcd"), std::string::npos) << error;
  EXPECT_NE(error.find("degrees"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;  // one line

  io::CloudPair missing;
  error.clear();
  EXPECT_FALSE(io::loadCloudPair(dir.file("none.pcd"), dir.file("plain.pcd"), missing, error));
  EXPECT_NE(error.find("none.pcd"), std::string::npos) << error;
}

}  // namespace
