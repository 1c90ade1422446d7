// pcl_ls3d_segment end to end: SEGMENTS.pcd keeps every input point in order with labels that
// match the JSON report, -evaluate prints the table, and bad input exits non-zero with exactly
// one error line. Runs the built tool (PCL_LS3D_TOOL_DIR) on a small generated PCD.
#include "evaluation/segmentation_test_scene.h"

#include <pcl_ls3d/evaluation/segmentation_labels.h>
#include <pcl_ls3d/evaluation/segmentation_runner.h>

#include <pcl/io/pcd_io.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {
struct ToolResult
{
  int code = -1;
  std::string out, err;
};

std::string
slurp(const fs::path& p)
{
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::size_t
countNonEmptyLines(const std::string& s)
{
  std::istringstream is(s);
  std::size_t n = 0;
  for (std::string line; std::getline(is, line);)
    n += line.find_first_not_of(" \t\r") != std::string::npos;
  return n;
}

class SegmentTool : public ::testing::Test
{
 protected:
  void
  SetUp() override
  {
    dir_ = fs::temp_directory_path() /
           ("pcl_ls3d_segment_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    tool_ = fs::path(PCL_LS3D_TOOL_DIR) / "pcl_ls3d_segment";
    if (!fs::exists(tool_))
      FAIL() << "tool not built: " << tool_;
    scene_ = pcl_ls3d_test::makeSmallScene();
    input_ = dir_ / "scene.pcd";
    ASSERT_EQ(pcl::io::savePCDFileBinary(input_.string(), scene_), 0);
  }
  void
  TearDown() override
  {
    fs::remove_all(dir_);
  }
  ToolResult
  run(const std::string& args)
  {
    ToolResult r;
    const std::string cmd = tool_.string() + " " + args + " > " + (dir_ / "out.txt").string() +
                            " 2> " + (dir_ / "err.txt").string();
    const int status = std::system(cmd.c_str());
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(dir_ / "out.txt");
    r.err = slurp(dir_ / "err.txt");
    return r;
  }

  fs::path dir_, tool_, input_;
  pcl::PointCloud<pcl::PointXYZL> scene_;
};
}  // namespace

TEST_F(SegmentTool, WritesEveryPointInOrderWithConsistentLabels)
{
  const fs::path out = dir_ / "segments.pcd", js = dir_ / "report.json";
  const ToolResult r = run(input_.string() + " -o " + out.string() + " -json " + js.string());
  ASSERT_EQ(r.code, 0) << r.err;
  pcl::PointCloud<pcl::PointXYZRGBL> seg;
  ASSERT_EQ(pcl::io::loadPCDFile(out.string(), seg), 0);
  ASSERT_EQ(seg.size(), scene_.size());
  // Coordinates below 1e4 are not shifted (origin 0), so float values round-trip exactly.
  for (std::size_t i = 0; i < seg.size(); i += 97) {
    EXPECT_EQ(seg[i].x, scene_[i].x) << i;
    EXPECT_EQ(seg[i].z, scene_[i].z) << i;
  }
  const auto report = nlohmann::json::parse(slurp(js));
  const auto& run0 = report["runs"][0];
  const std::size_t segments = run0["segments"].get<std::size_t>();
  ASSERT_GT(segments, 0u);
  // Labels are 1..segments (0 = none), every id used, same colour for the same label.
  std::set<std::uint32_t> used;
  std::map<std::uint32_t, std::uint32_t> colour;
  for (const auto& p : seg.points) {
    EXPECT_LE(p.label, segments);
    if (p.label == 0)
      continue;
    used.insert(p.label);
    const auto it = colour.emplace(p.label, p.rgba).first;
    EXPECT_EQ(it->second, p.rgba);
  }
  EXPECT_EQ(used.size(), segments);
  // The report carries the adaptive thresholds and the dimensionality counts of every point.
  EXPECT_TRUE(run0["thresholds"]["v_t_m"].is_number());
  EXPECT_TRUE(run0["thresholds"]["d_t_m"].is_number());
  const auto& d = run0["dimensionality"];
  EXPECT_EQ(d["linear"].get<std::size_t>() + d["planar"].get<std::size_t>() +
                d["volumetric"].get<std::size_t>() + d["invalid"].get<std::size_t>(),
            scene_.size());
  EXPECT_GE(run0["segments_before_merging"].get<std::size_t>(), segments);

  // The labels are exactly the segments the library returns for the same points (the method is
  // deterministic: same input, same segments).
  pcl::PointCloud<pcl::PointXYZ>::Ptr xyz(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : scene_.points)
    xyz->push_back(pcl::PointXYZ(p.x, p.y, p.z));
  pcl_ls3d::evaluation::SegmentationRun in_process;
  std::string error;
  ASSERT_TRUE(pcl_ls3d::evaluation::runSegmentation(xyz, {}, in_process, error)) << error;
  ASSERT_EQ(in_process.segments.size(), segments);
  const auto expected = pcl_ls3d::evaluation::labelsFromSegments(in_process.segments, xyz->size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < seg.size(); ++i)
    mismatches += seg[i].label != expected[i];
  EXPECT_EQ(mismatches, 0u);

  // Existing output without -overwrite is refused (one error line), with it accepted.
  const ToolResult again = run(input_.string() + " -o " + out.string());
  EXPECT_NE(again.code, 0);
  EXPECT_EQ(countNonEmptyLines(again.err), 1u) << again.err;
  EXPECT_EQ(run(input_.string() + " -o " + out.string() + " -overwrite -mode mrg").code, 0);
}

TEST_F(SegmentTool, EvaluatePrintsOneTableForThreeMethods)
{
  const fs::path js = dir_ / "eval.json";
  const ToolResult r = run(input_.string() + " -evaluate -json " + js.string());
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* m : {"imrg |", "mrg |", "pcl_rg |", "ground P/R/F1"})
    EXPECT_NE(r.out.find(m), std::string::npos) << m << "\n" << r.out;
  const auto report = nlohmann::json::parse(slurp(js));
  ASSERT_EQ(report["evaluation"].size(), 3u);
  // The 30 unclassified points are excluded from every evaluation.
  EXPECT_EQ(report["evaluation"][0]["points_evaluated"].get<std::size_t>(), scene_.size() - 30);
}

TEST_F(SegmentTool, BadInputExitsNonZeroWithOneErrorLine)
{
  // NaN-only PCD.
  const fs::path nan_file = dir_ / "nan.pcd";
  {
    std::ofstream f(nan_file);
    f << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
         "WIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA ascii\n"
         "nan nan nan\nnan nan nan\nnan nan nan\n";
  }
  const std::string cases[] = {
      (dir_ / "missing.las").string(),               // missing file
      nan_file.string(),                             // no finite point
      input_.string() + " -bogus 3",                 // unknown option
      input_.string() + " -mode fancy",              // unknown mode
      input_.string() + " -Nt abc",                  // not a number
      input_.string() + " -k 50,10",                 // impossible range
      input_.string() + " -o " + input_.string(),    // output = input
      input_.string() + " -classes ground",          // bad class spec
      "",                                            // no input at all -> help, exit 1
  };
  for (const auto& args : cases) {
    const ToolResult r = run(args);
    EXPECT_NE(r.code, 0) << args;
    if (!args.empty()) {
      EXPECT_EQ(countNonEmptyLines(r.err), 1u) << args << "\n" << r.err;
    }
  }
  // The input is never touched by a refused run.
  pcl::PointCloud<pcl::PointXYZL> back;
  ASSERT_EQ(pcl::io::loadPCDFile(input_.string(), back), 0);
  EXPECT_EQ(back.size(), scene_.size());
  // -h succeeds.
  EXPECT_EQ(run("-h").code, 0);
}

TEST_F(SegmentTool, GeoreferencedInputKeepsInputCoordinatesInDouble)
{
  // The same scene shifted to UTM-like coordinates, as ASCII XYZ (read in double): the reader
  // picks a local origin, and SEGMENTS.pcd must give the input coordinates back, x y z FLOAT64.
  const double ox = 512345.678, oy = 5432109.876, oz = 250.0;
  const fs::path xyz = dir_ / "utm.xyz", out = dir_ / "utm_segments.pcd";
  {
    std::ofstream f(xyz);
    f.precision(12);
    for (const auto& p : scene_.points)
      f << (p.x + ox) << ' ' << (p.y + oy) << ' ' << (p.z + oz) << '\n';
  }
  const ToolResult r = run(xyz.string() + " -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPCDFile(out.string(), blob), 0);
  ASSERT_EQ(blob.width * blob.height, scene_.size());
  ASSERT_GE(blob.fields.size(), 3u);
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(blob.fields[k].datatype, pcl::PCLPointField::FLOAT64) << blob.fields[k].name;
  for (std::size_t i = 0; i < scene_.size(); i += 97) {
    double x = 0.0, y = 0.0;
    std::memcpy(&x, blob.data.data() + i * blob.point_step + blob.fields[0].offset, 8);
    std::memcpy(&y, blob.data.data() + i * blob.point_step + blob.fields[1].offset, 8);
    // Float local coordinates (< 100 m) carry ~1e-5 m; the file wrote 12 digits (1e-6 m).
    EXPECT_NEAR(x, scene_[i].x + ox, 1e-4) << i;
    EXPECT_NEAR(y, scene_[i].y + oy, 1e-4) << i;
  }
}
