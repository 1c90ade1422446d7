/// \file test_fuzz_regressions.cpp
/// \brief Replays every file in test/data/fuzz_regressions (inputs on which a fuzz target once
///        failed, kept with the extension that picks their reader) through loadCloud: each must
///        load with finite, consistently counted points or fail with one short line. See
///        fuzz/README.md for how a finding becomes a file here.

#include <pcl_ls3d/io/cloud_io.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

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
  }
  EXPECT_GT(files, 0u);
}
