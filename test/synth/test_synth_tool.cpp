// Runs the pcl_ls3d_synth tool: files written, truth.json consistent, refusals and bad options.
#include "io/tool_run.h"

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/synth/registration_pair.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace fs = std::filesystem;
using namespace pcl_ls3d;

namespace {

const std::string kTool = std::string(PCL_LS3D_TOOL_DIR) + "/pcl_ls3d_synth";

int
run(const std::string& args)
{
  const fs::path scratch = fs::temp_directory_path() / ("pcl_ls3d_synth_run_" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  const int code = pcl_ls3d_test::runToolMerged("pcl_ls3d_synth", args, scratch.string()).code;
  std::error_code ec;
  fs::remove_all(scratch, ec);
  return code;
}

fs::path
freshDir(const std::string& name)
{
  const fs::path dir = fs::temp_directory_path() / ("pcl_ls3d_synth_test_" + name);
  fs::remove_all(dir);
  return dir;
}

}  // namespace

// `pair` writes source/target/truth.json; the files hold the generator's points in global
// coordinates, and the truth is the generator's.
TEST(SynthTool, PairFilesAndTruth)
{
  if (!fs::exists(kTool))
    FAIL() << kTool << " not built";
  const fs::path dir = freshDir("pair");
  ASSERT_EQ(run("pair -seed 7 -size 60,50 -origin 500000,5000000,100 -o " + dir.string()), 0);
  for (const char* f : {"source.pcd", "target.pcd", "truth.json"})
    ASSERT_TRUE(fs::exists(dir / f)) << f;

  std::ifstream in(dir / "truth.json");
  const auto j = nlohmann::json::parse(in);
  synth::RegistrationPairSettings s;
  s.seed = 7;
  s.size_x = 60.0;
  s.size_y = 50.0;
  s.origin = Eigen::Vector3d(5e5, 5e6, 100.0);
  const auto pair = synth::makeRegistrationPair(s);
  const Eigen::Matrix4d G = pair.globalTruthMatrix();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c)
      EXPECT_DOUBLE_EQ(j["transformation"][r][c].get<double>(), G(r, c));

  pcl::PointCloud<PointLiDAR> source;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(io::loadCloud((dir / "source.pcd").string(), source, info, error)) << error;
  ASSERT_EQ(source.size(), pair.source->size());
  // Global coordinates agree to float rounding of the local values (< 1e-4 m here).
  for (std::size_t i = 0; i < source.size(); i += 97) {
    const Eigen::Vector3d file = source[i].getVector3fMap().cast<double>() + info.origin;
    const Eigen::Vector3d mine = (*pair.source)[i].getVector3fMap().cast<double>() + s.origin;
    ASSERT_LT((file - mine).norm(), 1e-3);
  }
}

// Existing files are kept without -overwrite; bad options fail with a non-zero exit.
TEST(SynthTool, RefusalsAndErrors)
{
  if (!fs::exists(kTool))
    FAIL() << kTool << " not built";
  const fs::path dir = freshDir("refuse");
  ASSERT_EQ(run("li -o " + dir.string()), 0);
  EXPECT_TRUE(fs::exists(dir / "reference.pcd"));
  EXPECT_TRUE(fs::exists(dir / "mate.pcd"));
  EXPECT_NE(run("li -o " + dir.string()), 0);  // exists, no -overwrite
  EXPECT_EQ(run("li -overwrite -o " + dir.string()), 0);
  EXPECT_NE(run("pair -bogus 1 -o " + dir.string()), 0);      // unknown option
  EXPECT_NE(run("pair -overlap 1.5 -o " + dir.string()), 0);  // impossible value
  EXPECT_NE(run("pair -overlap abc -o " + dir.string()), 0);  // not a number
  EXPECT_NE(run("pair -format e57 -o " + dir.string()), 0);
  EXPECT_NE(run("nothing -o " + dir.string()), 0);
  EXPECT_NE(run("pair"), 0);  // no -o
  EXPECT_EQ(run("-h"), 0);
}

// strips -split and scene write their files.
TEST(SynthTool, StripsAndScene)
{
  if (!fs::exists(kTool))
    FAIL() << kTool << " not built";
  const fs::path dir = freshDir("strips");
  ASSERT_EQ(run("strips -strips 2 -length 80 -swath 40 -density 1 -split -format las -o " + dir.string()), 0);
  for (const char* f : {"strips.las", "strip_1.las", "strip_2.las", "truth.json"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  // The LAS file keeps the strip ids, classes and times the generator set.
  pcl::PointCloud<PointLiDAR> strips;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(io::loadCloud((dir / "strips.las").string(), strips, info, error)) << error;
  std::size_t first = 0, second = 0, ground = 0;
  for (const auto& p : strips) {
    first += p.point_source_id == 1;
    second += p.point_source_id == 2;
    ground += p.classification == 2;
  }
  EXPECT_EQ(first + second, strips.size());
  EXPECT_EQ(first, second);
  EXPECT_GT(ground, strips.size() / 2);
  EXPECT_GT(strips.back().gps_time, strips.front().gps_time);
  const fs::path scene_dir = freshDir("scene");
  ASSERT_EQ(run("scene -size 50,50 -density 2 -format ply -o " + scene_dir.string()), 0);
  EXPECT_TRUE(fs::exists(scene_dir / "scene.ply"));
  EXPECT_TRUE(fs::exists(scene_dir / "truth.json"));
}
