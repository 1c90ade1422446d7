// pcl_ls3d_segment end to end: SEGMENTS.pcd keeps every input point in order with labels that
// match the JSON report, -evaluate prints the table, and bad input exits non-zero with exactly
// one error line. Runs the built tool (PCL_LS3D_TOOL_DIR) on a small generated PCD.
#include "evaluation/segmentation_test_scene.h"
#include "io/tool_run.h"

#include <pcl_ls3d/evaluation/segmentation_labels.h>
#include <pcl_ls3d/evaluation/segmentation_runner.h>
#include <pcl_ls3d/evaluation/segments_file.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/maps/png_io.h>
#include <pcl_ls3d/synth/scene.h>

#include <pcl/io/pcd_io.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {
using ToolResult = pcl_ls3d_test::ToolRun;

std::string
slurp(const fs::path& p)
{
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

/// Share of the points of reference class \a truth written as \a code (0 when there are none).
double
shareWritten(const std::map<int, std::map<int, std::size_t>>& truth_to_code, int truth, int code)
{
  const auto row = truth_to_code.find(truth);
  if (row == truth_to_code.end())
    return 0.0;
  std::size_t all = 0;
  for (const auto& [c, n] : row->second)
    all += n;
  const auto hit = row->second.find(code);
  return hit == row->second.end() ? 0.0 : static_cast<double>(hit->second) / static_cast<double>(all);
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
    dir_ = fs::temp_directory_path() / ("pcl_ls3d_segment_test_" + std::to_string(::getpid()) + "_" +
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
    return pcl_ls3d_test::runTool(tool_.filename().string(), args,
                                  dir_.string());  // tool_ is in the tool dir
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
  // Issue 11 defect 4: hull kinds of the segments before merging are reported (they add up to
  // the segments before merging) and qhull prints nothing.
  const auto& hulls = run0["segment_hulls"];
  EXPECT_EQ(hulls["tiny"].get<std::size_t>() + hulls["collinear"].get<std::size_t>() +
                hulls["flat"].get<std::size_t>() + hulls["solid"].get<std::size_t>(),
            run0["segments_before_merging"].get<std::size_t>());
  EXPECT_EQ(r.err.find("QH"), std::string::npos) << r.err;

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
  // Numbers of returns not one per point are refused with a reason, before any work.
  pcl_ls3d::evaluation::SegmentationRun refused;
  EXPECT_FALSE(pcl_ls3d::evaluation::runSegmentation(xyz, {}, refused, error,
                                                     std::vector<std::uint8_t>(xyz->size() + 1, 1)));
  EXPECT_NE(error.find("numbers of returns for"), std::string::npos) << error;
  EXPECT_TRUE(refused.segments.empty());

  // Existing output without -overwrite is refused (one error line), with it accepted.
  const ToolResult again = run(input_.string() + " -o " + out.string());
  EXPECT_NE(again.code, 0);
  EXPECT_EQ(countNonEmptyLines(again.err), 1u) << again.err;
  EXPECT_EQ(run(input_.string() + " -o " + out.string() + " -overwrite -mode mrg").code, 0);
}

TEST_F(SegmentTool, EvaluatePrintsPointTableForFourMethods)
{
  const fs::path js = dir_ / "eval.json";
  const ToolResult r = run(input_.string() + " -evaluate -json " + js.string());
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* m : {"imrg |", "mrg |", "pcl_rg |", "ground P/R/F1"})
    EXPECT_NE(r.out.find(m), std::string::npos) << m << "\n" << r.out;
  const auto report = nlohmann::json::parse(slurp(js));
  ASSERT_EQ(report["evaluation"].size(), 4u);
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
  const fs::path few = dir_ / "few.xyz";
  std::ofstream(few) << "0 0 0\n1 0 0\n0 1 0\n1 1 0.1\n2 0 0\n";
  const std::string cases[] = {
      (dir_ / "missing.las").string(),                  // missing file
      nan_file.string(),                                // no finite point
      input_.string() + " -bogus 3",                    // unknown option
      input_.string() + " -mode fancy",                 // unknown mode
      input_.string() + " -Nt abc",                     // not a number
      input_.string() + " -k 50,10",                    // impossible range
      input_.string() + " -o " + input_.string(),       // output = input
      input_.string() + " -classes ground",             // bad class spec
      input_.string() + " -min_fragment -5",            // negative count (was silently the default)
      input_.string() + " -threads 1 -threads abc",     // repeated option (was: first value used)
      input_.string() + " -mode pcl_rg -level planes",  // -level means nothing to pcl_rg
      input_.string() + " -o /proc/pcl_ls3d_seg.pcd",   // no file can be created there, even as root
      input_.string() + " -json /proc/pcl_ls3d_seg.json",
      few.string(),  // fewer points than the smallest neighbourhood
      "",            // no input at all -> help, exit 1
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

TEST_F(SegmentTool, GeoreferencedInputLoadsInPlainPcl)
{
  // Issue 11 defect 1: the same scene shifted to UTM-like coordinates, as ASCII XYZ (read in
  // double). SEGMENTS.pcd must load with plain pcl::io::loadPCDFile into pcl::PointXYZRGBL
  // (float x y z in the local frame) and the origin line of its header must give the input
  // coordinates back.
  const double ox = 512345.678, oy = 5432109.876, oz = 250.0;
  const fs::path xyz = dir_ / "utm.xyz", out = dir_ / "utm_segments.pcd", js = dir_ / "r.json";
  {
    std::ofstream f(xyz);
    f.precision(12);
    for (const auto& p : scene_.points)
      f << (p.x + ox) << ' ' << (p.y + oy) << ' ' << (p.z + oz) << '\n';
  }
  const ToolResult r = run(xyz.string() + " -o " + out.string() + " -json " + js.string());
  ASSERT_EQ(r.code, 0) << r.err;
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPCDFile(out.string(), blob), 0);
  for (const auto& f : blob.fields) {
    if (f.name == "x" || f.name == "y" || f.name == "z") {
      EXPECT_EQ(f.datatype, pcl::PCLPointField::FLOAT32) << f.name;
    }
  }
  pcl::PointCloud<pcl::PointXYZRGBL> seg;
  ASSERT_EQ(pcl::io::loadPCDFile(out.string(), seg), 0);
  ASSERT_EQ(seg.size(), scene_.size());
  Eigen::Vector3d origin;
  ASSERT_TRUE(pcl_ls3d::evaluation::readSegmentsOrigin(out.string(), origin));
  const auto report = nlohmann::json::parse(slurp(js));
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(report["origin"][k].get<double>(), origin[k]);  // %.17g: exact
  EXPECT_NE(origin.x(), 0.0);
  std::size_t at_zero = 0;
  for (std::size_t i = 0; i < scene_.size(); ++i) {
    at_zero += seg[i].x == 0.f && seg[i].y == 0.f && seg[i].z == 0.f;
    // Local floats of < 100 m carry ~1e-5 m; the XYZ file has 12 digits (1e-6 m).
    ASSERT_NEAR(seg[i].x + origin.x(), scene_[i].x + ox, 1e-4) << i;
    ASSERT_NEAR(seg[i].y + origin.y(), scene_[i].y + oy, 1e-4) << i;
    ASSERT_NEAR(seg[i].z + origin.z(), scene_[i].z + oz, 1e-4) << i;
  }
  EXPECT_EQ(at_zero, 0u);
}

TEST_F(SegmentTool, NonFinitePointsKeepTheirPlaceWithLabelZero)
{
  // Issue 11 defect 2: NaN input points stay in SEGMENTS.pcd at their input index, label 0, so
  // the file lines up with the input point for point.
  pcl::PointCloud<pcl::PointXYZL> with_nan = scene_;
  std::set<std::size_t> bad;
  for (std::size_t i = 5; i < with_nan.size(); i += 11) {
    with_nan[i].x = std::numeric_limits<float>::quiet_NaN();
    bad.insert(i);
  }
  with_nan[0].z = std::numeric_limits<float>::infinity();
  bad.insert(0);
  with_nan.is_dense = false;
  const fs::path in = dir_ / "nan_scene.pcd", out = dir_ / "seg.pcd";
  ASSERT_EQ(pcl::io::savePCDFileBinary(in.string(), with_nan), 0);
  const ToolResult r = run(in.string() + " -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  pcl::PointCloud<pcl::PointXYZRGBL> seg;
  ASSERT_EQ(pcl::io::loadPCDFile(out.string(), seg), 0);
  ASSERT_EQ(seg.size(), with_nan.size());
  std::size_t labelled = 0;
  for (std::size_t i = 0; i < seg.size(); ++i) {
    if (bad.count(i)) {
      EXPECT_FALSE(std::isfinite(seg[i].x)) << i;
      EXPECT_EQ(seg[i].label, 0u) << i;
      continue;
    }
    ASSERT_EQ(seg[i].x, with_nan[i].x) << i;  // origin 0: exact
    ASSERT_EQ(seg[i].z, with_nan[i].z) << i;
    labelled += seg[i].label > 0;
  }
  EXPECT_GT(labelled, (seg.size() - bad.size()) / 2);
}

TEST_F(SegmentTool, EvaluatePrintsObjectTablesForFourMethods)
{
  const fs::path js = dir_ / "eval.json";
  const ToolResult r = run(input_.string() + " -evaluate -object_radius 3 -json " + js.string());
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* m : {"Object-based", "Fragmentation", "voxel |", "codes 0/1 excluded"})
    EXPECT_NE(r.out.find(m), std::string::npos) << m << "\n" << r.out;
  const auto report = nlohmann::json::parse(slurp(js));
  ASSERT_EQ(report["object_evaluation"].size(), 4u);
  // The scene holds one building (roof and sparse walls, within 3 m of each other), two tree
  // crowns 18 m apart and one ground piece: the reference objects come from the labels.
  EXPECT_EQ(report["reference_objects"]["radius_m"].get<double>(), 3.0);
  const auto& imrg = report["object_evaluation"][0];
  EXPECT_EQ(imrg["method"], "imrg");
  EXPECT_EQ(imrg["classes"]["building"]["objects"].get<int>(), 1);
  EXPECT_EQ(imrg["classes"]["vegetation"]["objects"].get<int>(), 2);
  EXPECT_EQ(imrg["classes"]["ground"]["objects"].get<int>(), 1);
  // The voxel grid was given IMRG's segment count (within the 1 % of its bisection, or the
  // nearest count a grid can give).
  const double n_imrg = report["runs"][0]["segments"].get<double>();
  const double n_voxel = report["runs"][3]["segments"].get<double>();
  EXPECT_NEAR(n_voxel, n_imrg, std::max(2.0, 0.1 * n_imrg));
}

TEST_F(SegmentTool, ScoredCodeOneIsNotCalledExcluded)
{
  // Issue 11 defect 6: with -classes naming code 1 the header must not claim it is excluded.
  const ToolResult r = run(input_.string() + " -evaluate -classes ground=2,building=6,vegetation=5,other=1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.find("0/1 excluded"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("code 0 excluded"), std::string::npos) << r.out;
}

TEST_F(SegmentTool, FailedBaselineIsARowNotTheRunsFailure)
{
  // Issue 11 defect 3: 4 points; pcl_rg (selected) keeps them as its rest segment, while the
  // multi-rule methods find no segment in fewer points than their smallest neighbourhood. Their failure is a row of
  // the tables; the selected method's result is still written, exit 0.
  pcl::PointCloud<pcl::PointXYZL> line;
  for (int i = 0; i < 4; ++i) {
    pcl::PointXYZL p;
    p.x = 0.5f * static_cast<float>(i);
    p.y = i == 3 ? 0.5f : 0.f;
    p.z = 0.f;
    p.label = 2;
    line.push_back(p);
  }
  const fs::path in = dir_ / "line.pcd", out = dir_ / "line_seg.pcd", js = dir_ / "line.json";
  ASSERT_EQ(pcl::io::savePCDFileBinary(in.string(), line), 0);
  const ToolResult r =
      run(in.string() + " -mode pcl_rg -evaluate -o " + out.string() + " -json " + js.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("failed:"), std::string::npos) << r.out;
  const auto report = nlohmann::json::parse(slurp(js));
  std::size_t failures = 0;
  for (const auto& e : report["object_evaluation"])
    failures += e.contains("failure");
  EXPECT_GE(failures, 1u);
  EXPECT_LT(failures, report["object_evaluation"].size());
  pcl::PointCloud<pcl::PointXYZRGBL> seg;
  ASSERT_EQ(pcl::io::loadPCDFile(out.string(), seg), 0);
  EXPECT_EQ(seg.size(), line.size());
}

TEST_F(SegmentTool, PlaneLevelGivesThePlanesBeforeMerging)
{
  // -level planes writes the segments before merging: the same as the library's plane level,
  // and the objects are (up to 1 % of the points) unions of whole planes.
  const fs::path out = dir_ / "planes.pcd";
  const ToolResult r = run(input_.string() + " -level planes -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  pcl::PointCloud<pcl::PointXYZRGBL> seg;
  ASSERT_EQ(pcl::io::loadPCDFile(out.string(), seg), 0);
  pcl::PointCloud<pcl::PointXYZ>::Ptr xyz(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : scene_.points)
    xyz->push_back(pcl::PointXYZ(p.x, p.y, p.z));
  pcl_ls3d::evaluation::SegmentationRunSettings s;
  s.level = pcl_ls3d::evaluation::SegmentationLevel::Planes;
  pcl_ls3d::evaluation::SegmentationRun planes;
  std::string error;
  ASSERT_TRUE(pcl_ls3d::evaluation::runSegmentation(xyz, s, planes, error)) << error;
  const auto expected = pcl_ls3d::evaluation::labelsFromSegments(planes.segments, xyz->size());
  ASSERT_EQ(seg.size(), expected.size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < seg.size(); ++i)
    mismatches += seg[i].label != expected[i];
  EXPECT_EQ(mismatches, 0u);
  const auto objects = pcl_ls3d::evaluation::labelsFromSegments(planes.other_level, xyz->size());
  EXPECT_GT(planes.segments.size(), planes.other_level.size());
  // Points outside their plane's majority object: object assembly decides ground per point,
  // so a few plane points may go elsewhere; nearly all stay with their plane.
  std::map<std::uint32_t, std::map<std::uint32_t, std::size_t>> objects_of_plane;
  std::size_t counted = 0;
  for (std::size_t i = 0; i < seg.size(); ++i)
    if (expected[i] > 0 && objects[i] > 0) {
      ++objects_of_plane[expected[i]][objects[i]];
      ++counted;
    }
  std::size_t outside = 0;
  for (const auto& [plane, hist] : objects_of_plane) {
    std::size_t total = 0, best = 0;
    for (const auto& [object, n] : hist) {
      total += n;
      best = std::max(best, n);
    }
    outside += total - best;
  }
  EXPECT_LE(static_cast<double>(outside), 0.01 * static_cast<double>(counted));
  EXPECT_NE(run(input_.string() + " -level walls").code, 0);
}

// render_top_view (the viewing aid behind the docs' pictures): a picture of the tool's
// SEGMENTS.pcd is written and readable; an empty input (PCL's PCD reader crashed on it) and an
// unwritable PNG (it said "Wrote" and exited 0) each exit 1 with one error line and no file.
TEST_F(SegmentTool, TopViewRefusesEmptyInputAndUnwritableOutput)
{
  const fs::path viewer = fs::path(PCL_LS3D_TOOL_DIR) / "render_top_view";
  if (!fs::exists(viewer))
    GTEST_SKIP() << "render_top_view not built (PCL_LS3D_BUILD_BENCHMARKS=OFF)";
  const fs::path seg = dir_ / "SEGMENTS.pcd";
  ASSERT_EQ(run(input_.string() + " -o " + seg.string()).code, 0);
  tool_ = viewer;
  const fs::path png = dir_ / "view.png";
  EXPECT_EQ(run(seg.string() + " " + png.string()).code, 0);
  pcl_ls3d::maps::Image image;
  std::string error;
  ASSERT_TRUE(pcl_ls3d::maps::readPng(png.string(), image, error)) << error;
  EXPECT_GT(image.width(), 10);
  {
    std::ofstream(dir_ / "empty.pcd");
  }
  ToolResult r = run((dir_ / "empty.pcd").string() + " " + (dir_ / "empty.png").string());
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "empty.png"));
  r = run(seg.string() + " " + (dir_ / "no_such_folder" / "x.png").string());
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(r.out.find("Wrote"), std::string::npos) << r.out;
  // Options are checked like every tool's: one line, exit 1, the existing PNG kept.
  const auto before = fs::last_write_time(png);
  for (const char* bad : {" -foo", " -by colour", " -pixel 0.1x", " -crop 5,1,0,1", ""}) {
    r = run(seg.string() + " " + png.string() + bad);  // "": exists, no -overwrite
    EXPECT_EQ(r.code, 1) << bad;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << ": " << r.err;
  }
  EXPECT_EQ(fs::last_write_time(png), before);
  EXPECT_EQ(run(seg.string() + " " + png.string() + " -overwrite -crop 1e6,2e6,0,1").code, 1);
  EXPECT_EQ(run("-h").code, 0);
}

// The tool's own SEGMENTS.pcd holds segment ids in its label field: -evaluate on it scored them
// as classes (F1 1.0, exit 0). It is now refused with one line before any work.
TEST_F(SegmentTool, EvaluateRefusesItsOwnSegmentsFile)
{
  const fs::path seg = dir_ / "SEGMENTS.pcd";
  ASSERT_EQ(run(input_.string() + " -o " + seg.string()).code, 0);
  EXPECT_TRUE(pcl_ls3d::evaluation::isSegmentsFile(seg.string()));
  EXPECT_FALSE(pcl_ls3d::evaluation::isSegmentsFile(input_.string()));
  const ToolResult r = run(seg.string() + " -evaluate");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("segment ids"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("F1"), std::string::npos) << r.out;
}

// pcl::RegionGrowing leaves the points of clusters under its minimum size unassigned: they are
// one "rest" segment for the evaluation only; SEGMENTS.pcd gives them label 0 (no segment).
TEST_F(SegmentTool, PclRegionGrowingRestIsLabelZero)
{
  const fs::path out = dir_ / "rg.pcd", json = dir_ / "rg.json";
  const ToolResult r = run(input_.string() + " -mode pcl_rg -o " + out.string() + " -json " + json.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  std::size_t rest = 0, segments = 0;
  for (const auto& run : j["runs"])
    if (run["method"] == "pcl_rg") {
      rest = run["rest_points"].get<std::size_t>();
      segments = run["segments"].get<std::size_t>();
    }
  ASSERT_GT(rest, 0u) << "the scene should leave some points to PCL's rest";
  pcl::PointCloud<pcl::PointXYZL> labelled;
  ASSERT_EQ(pcl::io::loadPCDFile(out.string(), labelled), 0);
  std::size_t unlabelled = 0;
  std::set<std::uint32_t> ids;
  for (const auto& p : labelled) {
    unlabelled += p.label == 0;
    if (p.label)
      ids.insert(p.label);
  }
  EXPECT_EQ(unlabelled, rest);
  EXPECT_EQ(ids.size(), segments - 1);
}

// One stray point 30 km away stretches the extent that the ground grid and the origin come
// from: the tool says so (stderr) instead of segmenting silently differently; the clean scene
// gets no such warning.
TEST_F(SegmentTool, FarOutlierIsWarnedAbout)
{
  ASSERT_GE(scene_.size(), 1000u);
  pcl::PointCloud<pcl::PointXYZL> stray = scene_;
  pcl::PointXYZL far = stray[0];
  far.x += 30000.0f;
  stray.push_back(far);
  const fs::path in = dir_ / "stray.pcd";
  ASSERT_EQ(pcl::io::savePCDFileBinary(in.string(), stray), 0);
  const ToolResult with = run(in.string());
  EXPECT_EQ(with.code, 0) << with.err;
  EXPECT_NE(with.err.find("far outliers"), std::string::npos) << with.err;
  const ToolResult clean = run(input_.string());
  EXPECT_EQ(clean.code, 0) << clean.err;
  EXPECT_EQ(clean.err.find("far outliers"), std::string::npos) << clean.err;
}

// The small scene (6 pulses per m² on ground and roof) thinned to every 8th point is below
// 1 point per m²: the tool warns that objects will join before it runs; the scene itself is
// dense enough and gets no such warning.
TEST_F(SegmentTool, SparseDataIsWarnedAbout)
{
  pcl::PointCloud<pcl::PointXYZL> sparse;
  for (std::size_t i = 0; i < scene_.size(); i += 8)
    sparse.push_back(scene_[i]);
  const fs::path in = dir_ / "sparse.pcd", json = dir_ / "sparse.json";
  ASSERT_EQ(pcl::io::savePCDFileBinary(in.string(), sparse), 0);
  const ToolResult thin = run(in.string() + " -json " + json.string());
  EXPECT_EQ(thin.code, 0) << thin.err;
  EXPECT_NE(thin.err.find("too sparse for whole objects"), std::string::npos) << thin.err;
  std::ifstream report(json);
  const nlohmann::json j = nlohmann::json::parse(report);
  ASSERT_EQ(j["warnings"].size(), 1u);  // and the report keeps it
  EXPECT_NE(j["warnings"][0].get<std::string>().find("too sparse"), std::string::npos);
  const ToolResult dense = run(input_.string());
  EXPECT_EQ(dense.code, 0) << dense.err;
  EXPECT_EQ(dense.err.find("too sparse"), std::string::npos) << dense.err;
}

namespace {
/// Where render_top_view put the picture in its map: "picture W x H pixels of P at X,Y".
bool
parsePicturePlacement(const std::string& out, int& w, int& h, int& x, int& y)
{
  const auto at = out.find("picture ");
  double pixel = 0.0;
  return at != std::string::npos &&
         std::sscanf(out.c_str() + at, "picture %d x %d pixels of %lf at %d,%d", &w, &h, &pixel, &x, &y) == 5;
}
}  // namespace

// render_top_view draws a map: the picture framed by a margin (scale bar, north arrow or the
// side view's direction, legend or caption). The map is larger than the picture by the margin
// on every side, and its picture area is pixel for pixel the -plain image, whose size is the
// old one (the extent over the pixel size, plus one, in each direction).
TEST_F(SegmentTool, TopViewMapFramesThePlainPictureUnchanged)
{
  const fs::path viewer = fs::path(PCL_LS3D_TOOL_DIR) / "render_top_view";
  if (!fs::exists(viewer))
    GTEST_SKIP() << "render_top_view not built (PCL_LS3D_BUILD_BENCHMARKS=OFF)";
  const fs::path seg = dir_ / "SEGMENTS.pcd", plain_png = dir_ / "plain.png", map_png = dir_ / "map.png";
  ASSERT_EQ(run(input_.string() + " -o " + seg.string()).code, 0);
  tool_ = viewer;
  const ToolResult plain_run = run(seg.string() + " " + plain_png.string() + " -plain");
  ASSERT_EQ(plain_run.code, 0) << plain_run.err;
  const ToolResult map_run = run(seg.string() + " " + map_png.string());
  ASSERT_EQ(map_run.code, 0) << map_run.err;
  pcl_ls3d::maps::Image plain, map;
  std::string error;
  ASSERT_TRUE(pcl_ls3d::maps::readPng(plain_png.string(), plain, error)) << error;
  ASSERT_TRUE(pcl_ls3d::maps::readPng(map_png.string(), map, error)) << error;

  pcl::PointCloud<pcl::PointXYZRGBL> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile(seg.string(), cloud), 0);
  float x0 = cloud[0].x, x1 = x0, y0 = cloud[0].y, y1 = y0;
  std::set<std::uint32_t> segments;
  for (const auto& p : cloud) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    if (p.label != 0)
      segments.insert(p.label);
  }
  EXPECT_EQ(plain.width(), static_cast<int>((x1 - x0) / 0.25) + 1);
  EXPECT_EQ(plain.height(), static_cast<int>((y1 - y0) / 0.25) + 1);

  int w = 0, h = 0, ox = -1, oy = -1;
  ASSERT_TRUE(parsePicturePlacement(map_run.out, w, h, ox, oy)) << map_run.out;
  EXPECT_EQ(w, plain.width());
  EXPECT_EQ(h, plain.height());
  ASSERT_GT(ox, 0);
  ASSERT_GT(oy, 0);
  EXPECT_GE(map.width(), ox + plain.width() + ox);
  EXPECT_GE(map.height(), oy + plain.height() + oy);
  std::size_t differing = 0;
  for (int y = 0; y < plain.height(); ++y)
    for (int x = 0; x < plain.width(); ++x)
      differing += !(map.get(ox + x, oy + y) == plain.get(x, y));
  EXPECT_EQ(differing, 0u);
  // The caption counts what the picture shows; a side view names its direction.
  const std::string caption = "Caption: " + std::to_string(segments.size()) + " segments, " +
                              std::to_string(cloud.size()) + " points, top view, pixel 0.25 m";
  EXPECT_NE(map_run.out.find(caption), std::string::npos) << map_run.out;
  const ToolResult side = run(seg.string() + " " + map_png.string() + " -overwrite -view north");
  ASSERT_EQ(side.code, 0) << side.err;
  EXPECT_NE(side.out.find("side view looking north"), std::string::npos) << side.out;
}

// -by class: the legend shows a swatch in the colour of each class in the picture, and none of
// another class: a cloud of ground (2) and building (6) has exactly those two class colours in
// its margin; the full scene adds high vegetation (5). Anti-aliased text and the frame are grey,
// so no other pixel of the margin has a class colour.
TEST_F(SegmentTool, TopViewClassLegendShowsTheClassesPresent)
{
  const fs::path viewer = fs::path(PCL_LS3D_TOOL_DIR) / "render_top_view";
  if (!fs::exists(viewer))
    GTEST_SKIP() << "render_top_view not built (PCL_LS3D_BUILD_BENCHMARKS=OFF)";
  tool_ = viewer;
  // The tool's ASPRS palette (render_top_view.cpp, classColour) of classes 2–6, 9, 14, 15, 64.
  const std::map<int, std::uint32_t> palette = {{2, 0xa0785a},  {3, 0x9ad07a},  {4, 0x4caf50},
                                                {5, 0x1b5e20},  {6, 0xd03030},  {9, 0x3070ff},
                                                {14, 0xffe000}, {15, 0xff8c00}, {64, 0x2040c0}};
  auto marginColours = [&](const fs::path& cloud) -> std::set<int> {
    const fs::path png = dir_ / "classes.png";
    const ToolResult r = run(cloud.string() + " " + png.string() + " -by class -overwrite");
    EXPECT_EQ(r.code, 0) << r.err;
    pcl_ls3d::maps::Image map;
    std::string error;
    EXPECT_TRUE(pcl_ls3d::maps::readPng(png.string(), map, error)) << error;
    int w = 0, h = 0, ox = 0, oy = 0;
    if (!parsePicturePlacement(r.out, w, h, ox, oy)) {
      ADD_FAILURE() << "no picture placement (no margin) in: " << r.out;
      return {};
    }
    std::set<int> found;
    for (int y = 0; y < map.height(); ++y)
      for (int x = 0; x < map.width(); ++x) {
        if (x >= ox && x < ox + w && y >= oy && y < oy + h)
          continue;  // the picture itself
        const pcl_ls3d::maps::Rgb c = map.get(x, y);
        for (const auto& [code, rgb] : palette)
          if (c.r == (rgb >> 16 & 0xff) && c.g == (rgb >> 8 & 0xff) && c.b == (rgb & 0xff))
            found.insert(code);
      }
    return found;
  };
  pcl::PointCloud<pcl::PointXYZL> two;
  for (const auto& p : scene_)
    if (p.label == 2 || p.label == 6)
      two.push_back(p);
  ASSERT_GT(two.size(), 1000u);
  const fs::path two_pcd = dir_ / "ground_building.pcd";
  ASSERT_EQ(pcl::io::savePCDFileBinary(two_pcd.string(), two), 0);
  EXPECT_EQ(marginColours(two_pcd), (std::set<int>{2, 6}));
  EXPECT_EQ(marginColours(input_), (std::set<int>{2, 5, 6}));
}

// The scale bar's label is a round length (1, 2 or 5 × 10^k m) and the bar is that length over
// the pixel size, rounded to a pixel: as printed, and as drawn (its top edge is one dark run of
// exactly that many pixels), also at 0.3 m pixels, where the ratio is not whole.
TEST_F(SegmentTool, TopViewScaleBarMatchesItsLabel)
{
  const fs::path viewer = fs::path(PCL_LS3D_TOOL_DIR) / "render_top_view";
  if (!fs::exists(viewer))
    GTEST_SKIP() << "render_top_view not built (PCL_LS3D_BUILD_BENCHMARKS=OFF)";
  tool_ = viewer;
  const fs::path png = dir_ / "bar.png";
  for (const double pixel : {0.25, 0.3}) {
    const ToolResult r =
        run(input_.string() + " " + png.string() + " -overwrite -pixel " + std::to_string(pixel));
    ASSERT_EQ(r.code, 0) << r.err;
    const auto at = r.out.find("Scale bar ");
    ASSERT_NE(at, std::string::npos) << r.out;
    double length = 0.0;
    int pixels = 0, x = 0, y = 0;
    char unit[8] = {};
    ASSERT_EQ(
        std::sscanf(r.out.c_str() + at, "Scale bar %lf %7s = %d px at %d,%d", &length, unit, &pixels, &x, &y),
        5)
        << r.out;
    EXPECT_STREQ(unit, "m");  // a PCD declares no CRS: metres
    EXPECT_EQ(pixels, std::lround(length / pixel)) << length << " m at " << pixel;
    const double mantissa = length / std::pow(10.0, std::floor(std::log10(length)));
    EXPECT_TRUE(std::abs(mantissa - 1.0) < 1e-9 || std::abs(mantissa - 2.0) < 1e-9 ||
                std::abs(mantissa - 5.0) < 1e-9)
        << length;
    pcl_ls3d::maps::Image map;
    std::string error;
    ASSERT_TRUE(pcl_ls3d::maps::readPng(png.string(), map, error)) << error;
    auto dark = [&map](int px, int py) {
      const pcl_ls3d::maps::Rgb c = map.get(px, py);
      return c.r < 100 && c.g < 100 && c.b < 100;
    };
    int run_length = 0;
    while (x + run_length < map.width() && dark(x + run_length, y))
      ++run_length;
    EXPECT_FALSE(dark(x - 1, y));
    EXPECT_EQ(run_length, pixels) << "at " << pixel << " m pixels";
  }
}

// IMRG names its objects: SEGMENTS.pcd carries a classification byte per point, the LAS code
// of its segment's class as the JSON names it (segment_classes, index = label - 1); plain PCL
// still loads the file into PointXYZRGBL with the same labels. Against the scene's truth the
// roof is building, the terrain ground and the crowns vegetation. pcl_ls3d_info counts the
// object classes; pcl_ls3d_convert writes them into a LAS file's classification.
TEST_F(SegmentTool, SegmentsFileCarriesObjectClasses)
{
  const fs::path seg = dir_ / "SEGMENTS.pcd", js = dir_ / "report.json", las = dir_ / "classes.las";
  const ToolResult r = run(input_.string() + " -o " + seg.string() + " -json " + js.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("imrg classes: "), std::string::npos) << r.out;
  const auto report = nlohmann::json::parse(slurp(js));
  ASSERT_TRUE(report.contains("segment_classes")) << report.dump();
  const auto names = report["segment_classes"].get<std::vector<std::string>>();
  ASSERT_EQ(names.size(), report["runs"][0]["segments"].get<std::size_t>());

  pcl::PointCloud<pcl::PointXYZRGBL> plain;
  ASSERT_EQ(pcl::io::loadPCDFile(seg.string(), plain), 0);
  pcl::PointCloud<pcl_ls3d::PointLiDAR> lidar;
  pcl_ls3d::io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(pcl_ls3d::io::loadCloud(seg.string(), lidar, info, error)) << error;
  ASSERT_EQ(plain.size(), scene_.size());
  ASSERT_EQ(lidar.size(), scene_.size());
  const std::map<std::string, int> code = {{"unclassified", 1}, {"ground", 2}, {"building", 6},
                                           {"vegetation", 5},   {"wire", 14},  {"pole", 15},
                                           {"car", 64}};
  std::map<int, std::map<int, std::size_t>> truth_to_class;  // scene label -> written code
  for (std::size_t i = 0; i < plain.size(); ++i) {
    const std::uint32_t label = plain[i].label;
    const int expected = label == 0 ? 0 : code.at(names.at(label - 1));
    ASSERT_EQ(static_cast<int>(lidar[i].classification), expected) << i;
    ++truth_to_class[static_cast<int>(scene_[i].label)][expected];
  }
  EXPECT_GE(shareWritten(truth_to_class, 2, 2), 0.95);
  EXPECT_GE(shareWritten(truth_to_class, 6, 6), 0.9);
  EXPECT_GE(shareWritten(truth_to_class, 5, 5), 0.9);

  const fs::path info_tool = fs::path(PCL_LS3D_TOOL_DIR) / "pcl_ls3d_info";
  tool_ = info_tool;
  const ToolResult described = run(seg.string());
  ASSERT_EQ(described.code, 0) << described.err;
  EXPECT_NE(described.out.find("object classes (LAS codes): "), std::string::npos) << described.out;
  for (const auto& [name, counts] : report["runs"][0]["classes"].items())  // same points per code
    EXPECT_NE(described.out.find(" " + std::to_string(code.at(name)) + ":" +
                                 std::to_string(counts["points"].get<std::size_t>())),
              std::string::npos)
        << name << "\n"
        << described.out;
  tool_ = fs::path(PCL_LS3D_TOOL_DIR) / "pcl_ls3d_convert";
  ASSERT_EQ(run(seg.string() + " " + las.string()).code, 0);
  pcl::PointCloud<pcl_ls3d::PointLiDAR> converted;
  ASSERT_TRUE(pcl_ls3d::io::loadCloud(las.string(), converted, info, error)) << error;
  ASSERT_EQ(converted.size(), lidar.size());
  for (std::size_t i = 0; i < converted.size(); i += 7)
    EXPECT_EQ(converted[i].classification, lidar[i].classification) << i;
}

// -evaluate scores IMRG's classes point by point against the reference labels (no reference
// used to name them), in the table and the JSON; MRG names nothing, so its SEGMENTS.pcd has no
// classification field, and render_top_view -by class refuses it in one line instead of
// painting segment ids as classes.
TEST_F(SegmentTool, EvaluateScoresObjectClassesAndMrgHasNone)
{
  const fs::path js = dir_ / "eval.json", mrg = dir_ / "mrg.pcd";
  const ToolResult r = run(input_.string() + " -evaluate -json " + js.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("Object classes, per point"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("imrg classes |"), std::string::npos) << r.out;
  const auto report = nlohmann::json::parse(slurp(js));
  ASSERT_EQ(report["class_evaluation"].size(), 1u) << report.dump();
  for (const char* name : {"ground", "building", "vegetation"})
    EXPECT_GE(report["class_evaluation"][0]["classes"][name]["f1"].get<double>(), 0.9) << name;

  ASSERT_EQ(run(input_.string() + " -mode mrg -o " + mrg.string()).code, 0);
  EXPECT_EQ(slurp(mrg).find("classification"), std::string::npos);
  const fs::path viewer = fs::path(PCL_LS3D_TOOL_DIR) / "render_top_view";
  if (!fs::exists(viewer))
    GTEST_SKIP() << "render_top_view not built (PCL_LS3D_BUILD_BENCHMARKS=OFF)";
  tool_ = viewer;
  const ToolResult refused = run(mrg.string() + " " + (dir_ / "c.png").string() + " -by class");
  EXPECT_EQ(refused.code, 1);
  EXPECT_EQ(countNonEmptyLines(refused.err), 1u) << refused.err;
  EXPECT_NE(refused.err.find("no object classes"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir_ / "c.png"));
}

// A georeferenced input's CRS travels with its segments: SEGMENTS.pcd records it in a header
// line (plain PCL still loads the file), pcl_ls3d_info names it, and pcl_ls3d_convert gives the
// LAS it writes that CRS (LAS 1.4, WKT VLR, global-encoding bit 4). Before, the CRS was lost
// and every picture of the segments said "no CRS in the file".
TEST_F(SegmentTool, SegmentsFileKeepsTheInputCrs)
{
  const std::string wkt = pcl_ls3d::maps::crsFromUserInput("EPSG:2154");  // Lambert-93
  ASSERT_FALSE(wkt.empty());
  pcl::PointCloud<pcl_ls3d::PointLiDAR> lidar;
  for (const auto& p : scene_) {
    pcl_ls3d::PointLiDAR q;
    q.x = p.x;
    q.y = p.y;
    q.z = p.z;
    q.classification = static_cast<std::uint8_t>(p.label);
    lidar.push_back(q);
  }
  pcl_ls3d::io::SaveOptions options;
  options.las_vlrs = {pcl_ls3d::maps::wktVlr(wkt)};
  const Eigen::Vector3d origin(770000.0, 6277000.0, 0.0);
  const fs::path las = dir_ / "scene.las", seg = dir_ / "SEGMENTS.pcd", back = dir_ / "back.las";
  std::string error;
  ASSERT_TRUE(pcl_ls3d::io::saveCloud(las.string(), lidar, origin, error, options)) << error;
  ASSERT_EQ(run(las.string() + " -o " + seg.string()).code, 0);
  EXPECT_NE(slurp(seg).find("\n# pcl_ls3d crs "), std::string::npos);
  pcl::PointCloud<pcl::PointXYZRGBL> plain;
  ASSERT_EQ(pcl::io::loadPCDFile(seg.string(), plain), 0);
  EXPECT_EQ(plain.size(), scene_.size());
  pcl::PointCloud<pcl_ls3d::PointLiDAR> loaded;
  pcl_ls3d::io::CloudInfo info;
  ASSERT_TRUE(pcl_ls3d::io::loadCloud(seg.string(), loaded, info, error)) << error;
  EXPECT_TRUE(pcl_ls3d::maps::sameCrs(info.file_crs_wkt, wkt)) << info.file_crs_wkt;

  tool_ = fs::path(PCL_LS3D_TOOL_DIR) / "pcl_ls3d_info";
  const ToolResult described = run(seg.string());
  EXPECT_NE(described.out.find("crs RGF93 v1 / Lambert-93 (recorded in the header)"), std::string::npos)
      << described.out;
  tool_ = fs::path(PCL_LS3D_TOOL_DIR) / "pcl_ls3d_convert";
  ASSERT_EQ(run(seg.string() + " " + back.string()).code, 0);
  ASSERT_TRUE(pcl_ls3d::io::loadCloud(back.string(), loaded, info, error)) << error;
  EXPECT_EQ(info.las.version_minor, 4);
  EXPECT_EQ(info.las.global_encoding & 16, 16);
  EXPECT_TRUE(pcl_ls3d::maps::sameCrs(pcl_ls3d::maps::crsFromLasVlrs(info.las.vlrs), wkt));
  EXPECT_NEAR(info.min_file.x(), origin.x() - 20.0, 1.0);  // the input's coordinates
}

// A projected CRS in feet (US State Plane, Oregon Lambert: PDAL's Autzen) is segmented in
// metres: the classes' heights and sizes are physical (a building 2 m up, a car 2.5-7 m long).
// Before, a generated scene written in international feet lost its cars (14.8 "m" long) and
// its ground (Autzen's trimmed strip: 1.9 % ground, 47 % "building"). SEGMENTS.pcd keeps the
// file's unit; the JSON says how many metres a unit is.
TEST_F(SegmentTool, FeetAreSegmentedInMetres)
{
  const std::string wkt = pcl_ls3d::maps::crsFromUserInput("EPSG:2994");  // Oregon GIC Lambert (ft)
  ASSERT_NEAR(pcl_ls3d::maps::crsLinearUnit(wkt), 0.3048, 1e-9);
  ASSERT_NEAR(pcl_ls3d::maps::crsVerticalUnit(wkt), 0.3048, 1e-9);
  pcl_ls3d::synth::SceneSettings settings;
  settings.seed = 4;
  settings.size_x = settings.size_y = 100.0;
  const auto scene = pcl_ls3d::synth::makeScene(settings);
  ASSERT_TRUE(scene.cloud && scene.cloud->size() > 50000u);
  pcl::PointCloud<pcl_ls3d::PointLiDAR> feet = *scene.cloud;
  for (auto& p : feet) {
    p.x /= 0.3048f;
    p.y /= 0.3048f;
    p.z /= 0.3048f;
  }
  pcl_ls3d::io::SaveOptions options;
  options.las_vlrs = {pcl_ls3d::maps::wktVlr(wkt)};
  options.las_point_format = 6;  // class 64 (cars) and the returns
  options.las_minor_version = 4;
  const fs::path las = dir_ / "feet.las", seg = dir_ / "SEGMENTS.pcd", js = dir_ / "r.json";
  std::string error;
  ASSERT_TRUE(
      pcl_ls3d::io::saveCloud(las.string(), feet, Eigen::Vector3d(2000000.0, 800000.0, 0.0), error, options))
      << error;
  const ToolResult r = run(las.string() + " -o " + seg.string() + " -json " + js.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("segmented in metres"), std::string::npos) << r.out;
  const auto report = nlohmann::json::parse(slurp(js));
  EXPECT_NEAR(report["metres_per_unit"]["horizontal"].get<double>(), 0.3048, 1e-9);
  EXPECT_NEAR(report["metres_per_unit"]["vertical"].get<double>(), 0.3048, 1e-9);

  pcl::PointCloud<pcl_ls3d::PointLiDAR> written;
  pcl_ls3d::io::CloudInfo info;
  ASSERT_TRUE(pcl_ls3d::io::loadCloud(seg.string(), written, info, error)) << error;
  ASSERT_EQ(written.size(), feet.size());
  std::map<int, std::map<int, std::size_t>> truth_to_class;  // generator code -> written code
  for (std::size_t i = 0; i < written.size(); ++i) {
    ASSERT_NEAR(written[i].x, feet[i].x, 0.02f) << i;  // the file's unit, not metres
    const int truth = feet[i].classification >= 3 && feet[i].classification <= 5 ? 5 : feet[i].classification;
    ++truth_to_class[truth][written[i].classification];
  }
  EXPECT_GE(shareWritten(truth_to_class, 2, 2), 0.95);
  EXPECT_GE(shareWritten(truth_to_class, 6, 6), 0.95);
  EXPECT_GE(shareWritten(truth_to_class, 5, 5), 0.9);
  EXPECT_GE(shareWritten(truth_to_class, 64, 64), 0.9);  // cars
}

// Latitude and longitude are no lengths: one error line before any work, nothing written.
TEST_F(SegmentTool, DegreesAreRefused)
{
  const std::string wkt = pcl_ls3d::maps::crsFromUserInput("EPSG:4326");
  ASSERT_TRUE(pcl_ls3d::maps::crsIsGeographic(wkt));
  EXPECT_FALSE(pcl_ls3d::maps::crsIsGeographic(pcl_ls3d::maps::crsFromUserInput("EPSG:2994")));
  pcl::PointCloud<pcl_ls3d::PointLiDAR> lidar;
  for (const auto& p : scene_)
    lidar.push_back(pcl_ls3d::PointLiDAR(p.x * 1e-5f, p.y * 1e-5f, p.z));
  pcl_ls3d::io::SaveOptions options;
  options.las_vlrs = {pcl_ls3d::maps::wktVlr(wkt)};
  const fs::path las = dir_ / "degrees.las", seg = dir_ / "SEGMENTS.pcd";
  std::string error;
  ASSERT_TRUE(pcl_ls3d::io::saveCloud(las.string(), lidar, Eigen::Vector3d(2.0, 48.0, 0.0), error, options))
      << error;
  const ToolResult r = run(las.string() + " -o " + seg.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(countNonEmptyLines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("degrees"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(seg));
}
