/// \file test_fuzz_regressions.cpp
/// \brief Replays every file in test/data/fuzz_regressions (inputs on which a fuzz target once
///        failed, kept with the extension that picks their reader) through loadCloud: each must
///        load with finite, consistently counted points or fail with one short line, and what
///        loads must survive every writer (PCD and PLY binary and ASCII, LAS, XYZ) and load again
///        with as many points, as load_cloud_fuzzer checks. See fuzz/README.md for how a finding
///        becomes a file here.

#include <pcl_ls3d/io/cloud_io.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

namespace {

/// Written by every writer and loaded again with the same origin: as many points, or the writer
/// refuses with a reason (e.g. LAS cannot quantise 1e72).
void
expectEveryWriterRoundTrips(const pcl::PointCloud<pcl_ls3d::PointLiDAR>& cloud, const Eigen::Vector3d& origin)
{
  const std::pair<const char*, bool> writers[] = {{"pcd", true},  {"pcd", false}, {"ply", true},
                                                  {"ply", false}, {"las", true},  {"xyz", false}};
  for (const auto& [ext, binary] : writers) {
    SCOPED_TRACE(std::string(ext) + (binary ? " binary" : " ascii"));
    const std::string path = ::testing::TempDir() + "ls3d_fuzz_regression." + ext;
    pcl_ls3d::io::SaveOptions save;
    save.overwrite = true;
    save.binary = binary;
    std::string error;
    if (!pcl_ls3d::io::saveCloud(path, cloud, origin, error, save)) {
      EXPECT_FALSE(error.empty());
      continue;
    }
    pcl::PointCloud<pcl_ls3d::PointLiDAR> again;
    pcl_ls3d::io::CloudInfo info;
    pcl_ls3d::io::LoadOptions load;
    load.use_origin = true;
    load.origin = origin;
    EXPECT_TRUE(pcl_ls3d::io::loadCloud(path, again, info, error, load)) << error;
    EXPECT_EQ(again.size(), cloud.size());
    fs::remove(path);
  }
}

}  // namespace

TEST(FuzzRegressions, EveryFindingLoadsOrFailsWithOneLine)
{
  const fs::path dir = fs::path(PCL_LS3D_TEST_SOURCE_DIR) / "data" / "fuzz_regressions";
  ASSERT_TRUE(fs::is_directory(dir)) << dir;
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".md")
      continue;
    SCOPED_TRACE(entry.path().string());
    ++files;
    pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
    pcl_ls3d::io::CloudInfo info;
    std::string error;
    pcl_ls3d::io::LoadOptions options;
    options.allow_empty = true;
    if (!pcl_ls3d::io::loadCloud(entry.path().string(), cloud, info, error, options)) {
      EXPECT_FALSE(error.empty());
      EXPECT_EQ(error.find('\n'), std::string::npos);
      EXPECT_LT(error.size(), 400u + entry.path().string().size());
      continue;
    }
    EXPECT_EQ(cloud.size(), info.points_loaded);
    EXPECT_EQ(info.points_loaded + info.points_dropped_nonfinite, info.points_in_file);
    EXPECT_TRUE(info.origin.allFinite());
    for (const auto& p : cloud)
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    expectEveryWriterRoundTrips(cloud, info.origin);
  }
  EXPECT_GT(files, 0u);
}
