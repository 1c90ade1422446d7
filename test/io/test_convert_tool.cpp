/// \file test_convert_tool.cpp
/// \brief pcl_ls3d_convert end to end: conversion, -split_strips, -classes, -origin, refusal to
///        overwrite the input or an existing output, one-line errors with a non-zero exit.

#include <pcl_ls3d/evaluation/segments_file.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/maps/coordinate_reference.h>

#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

#include "io/io_test_utils.h"
#include "io/tool_run.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <sstream>
#include <vector>

using namespace pcl_ls3d;
namespace fs = std::filesystem;

namespace {

const std::string kTool = std::string(PCL_LS3D_TOOL_DIR) + "/pcl_ls3d_convert";
const std::string kInfoTool = std::string(PCL_LS3D_TOOL_DIR) + "/pcl_ls3d_info";
const std::string kSegmentTool = std::string(PCL_LS3D_TOOL_DIR) + "/pcl_ls3d_segment";

std::size_t
occurrences(const std::string& text, const std::string& what)
{
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

/// Runs `tool` with `args`; returns the exit code and fills `output` (stdout + stderr).
int
runProgram(const std::string& tool, const std::string& args, std::string& output,
           const pcl_ls3d_test::TempDir& dir)
{
  const pcl_ls3d_test::ToolRun r = pcl_ls3d_test::runToolMerged(tool, args, dir.path.string());
  output = r.out;
  return r.code;
}

/// A LAS file's point coordinates read from its bytes (public header fields and the first 12
/// bytes of each record), not through pcl_ls3d's reader: the reference the tests compare with.
std::vector<Eigen::Vector3d>
rawLasCoordinates(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  const std::string b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto get = [&b](std::size_t at, auto value) {
    std::memcpy(&value, b.data() + at, sizeof(value));
    return value;
  };
  const std::uint32_t first = get(96, std::uint32_t());
  const std::uint16_t record = get(105, std::uint16_t());
  const std::uint32_t n = get(107, std::uint32_t());
  std::vector<Eigen::Vector3d> out;
  for (std::uint32_t i = 0; i < n; ++i)
    out.emplace_back(get(first + i * record, std::int32_t()) * get(131, 0.0) + get(155, 0.0),
                     get(first + i * record + 4, std::int32_t()) * get(139, 0.0) + get(163, 0.0),
                     get(first + i * record + 8, std::int32_t()) * get(147, 0.0) + get(171, 0.0));
  return out;
}

/// The origin from the "# pcl_ls3d origin X Y Z" header line, read as text.
bool
recordedOrigin(const std::string& path, Eigen::Vector3d& origin)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  while (std::getline(in, line) && line.rfind("DATA", 0) != 0)
    if (std::sscanf(line.c_str(), "# pcl_ls3d origin %lf %lf %lf", &origin[0], &origin[1], &origin[2]) == 3)
      return true;
  return false;
}

/// pcl_ls3d_convert with `args`.
int
run(const std::string& args, std::string& output, const pcl_ls3d_test::TempDir& dir)
{
  return runProgram("pcl_ls3d_convert", args, output, dir);
}

/// pcl_ls3d_info with `args`.
int
runInfo(const std::string& args, std::string& output, const pcl_ls3d_test::TempDir& dir)
{
  return runProgram("pcl_ls3d_info", args, output, dir);
}

class ConvertTool : public ::testing::Test
{
protected:
  void
  SetUp() override
  {
    if (!fs::exists(kTool))
      FAIL() << kTool << " is not built";
    // 3 strips (psid 10, 11, 12), classes 2 / 6 / 5 in turn, UTM coordinates.
    std::vector<Eigen::Vector3d> truth;
    pcl_ls3d_test::makeUtmCloud(300, 3, {600000.0, 5000000.0, 100.0}, origin_, cloud_, truth);
    for (std::size_t i = 0; i < cloud_.size(); ++i) {
      cloud_[i].point_source_id = static_cast<std::uint16_t>(10 + i % 3);
      cloud_[i].classification = i % 3 == 0 ? 2 : (i % 3 == 1 ? 6 : 5);
    }
    std::string error;
    ASSERT_TRUE(io::saveCloud(dir_.file("in.las"), cloud_, origin_, error)) << error;
  }

  /// SEGMENTS.pcd of in.las, written by pcl_ls3d_segment (ASSERT-fails the test when it is not).
  std::string
  segmentsFile()
  {
    const std::string seg = dir_.file("SEGMENTS.pcd");
    std::string out;
    if (!fs::exists(kSegmentTool))
      ADD_FAILURE() << kSegmentTool << " is not built";
    else
      EXPECT_EQ(runProgram("pcl_ls3d_segment", dir_.file("in.las") + " -o " + seg, out, dir_), 0) << out;
    return seg;
  }

  pcl_ls3d_test::TempDir dir_{"ls3d_convert"};
  Eigen::Vector3d origin_{600000.0, 5000000.0, 0.0};
  pcl::PointCloud<PointLiDAR> cloud_;
};

}  // namespace

TEST_F(ConvertTool, ConvertsAndRefusesToOverwrite)
{
  std::string out;
  ASSERT_EQ(run(dir_.file("in.las") + " " + dir_.file("out.pcd"), out, dir_), 0) << out;
  EXPECT_NE(out.find("Local origin (auto)"), std::string::npos) << out;
  pcl::PointCloud<PointLiDAR> back;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(io::loadCloud(dir_.file("out.pcd"), back, info, error)) << error;
  ASSERT_EQ(back.size(), cloud_.size());
  const Eigen::Vector3d x0 = back[0].getVector3fMap().cast<double>() + info.origin;
  const Eigen::Vector3d t0 = cloud_[0].getVector3fMap().cast<double>() + origin_;
  EXPECT_LT((x0 - t0).cwiseAbs().maxCoeff(), 1e-3);

  EXPECT_NE(run(dir_.file("in.las") + " " + dir_.file("out.pcd"), out, dir_), 0);
  EXPECT_NE(out.find("exists already"), std::string::npos) << out;
  EXPECT_EQ(run(dir_.file("in.las") + " " + dir_.file("out.pcd") + " -overwrite", out, dir_), 0) << out;

  const auto size_before = fs::file_size(dir_.file("in.las"));
  EXPECT_NE(run(dir_.file("in.las") + " " + dir_.path.string() + "/./in.las -overwrite", out, dir_), 0);
  EXPECT_NE(out.find("is the input file"), std::string::npos) << out;
  EXPECT_EQ(fs::file_size(dir_.file("in.las")), size_before);
}

TEST_F(ConvertTool, SplitStripsAndFilterClasses)
{
  std::string out;
  const std::string strips = dir_.file("strips");
  ASSERT_EQ(run(dir_.file("in.las") + " -split_strips " + strips + " -classes 2,6", out, dir_), 0) << out;
  // psid = 10 + i%3 and the class follows i%3 too: strips 10 (class 2) and 11 (class 6) keep all
  // 100 points; strip 12 (class 5) is filtered out before splitting and gets no file.
  for (int id : {10, 11}) {
    const std::string path = strips + "/in_psid" + std::to_string(id) + ".las";
    pcl::PointCloud<PointLiDAR> strip;
    io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(io::loadCloud(path, strip, info, error)) << error;
    EXPECT_EQ(strip.size(), 100u) << path;
    for (const auto& p : strip)
      EXPECT_EQ(p.point_source_id, id);
  }
  EXPECT_FALSE(fs::exists(strips + "/in_psid12.las"));
}

TEST_F(ConvertTool, ForcedOriginAndFormats)
{
  std::string out;
  ASSERT_EQ(run(dir_.file("in.las") + " " + dir_.file("out.xyz") + " -origin 600100,5000100,0", out, dir_), 0)
      << out;
  EXPECT_NE(out.find("Local origin (forced): 600100.000 5000100.000 0.000"), std::string::npos) << out;
  ASSERT_EQ(run(dir_.file("out.xyz") + " " + dir_.file("back.las") + " -las_format 6", out, dir_), 0) << out;
  pcl::PointCloud<PointLiDAR> back;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(io::loadCloud(dir_.file("back.las"), back, info, error)) << error;
  EXPECT_EQ(info.las.point_format, 6);
  EXPECT_EQ(info.las.version_minor, 4);
  EXPECT_EQ(back.size(), cloud_.size());
}

TEST_F(ConvertTool, BadInputGivesOneErrorLineAndNonZeroExit)
{
  std::string out;
  EXPECT_NE(run(dir_.file("in.las") + " " + dir_.file("o.pcd") + " -bogus", out, dir_), 0);
  EXPECT_NE(out.find("Unknown option -bogus"), std::string::npos) << out;
  EXPECT_NE(run(dir_.file("missing.las") + " " + dir_.file("o.pcd"), out, dir_), 0);
  EXPECT_NE(out.find("does not exist"), std::string::npos) << out;
  {
    // A LAZ file that lost its LASzip VLR: the compression bit alone.
    std::ifstream in(dir_.file("in.las"), std::ios::binary);
    std::string las((std::istreambuf_iterator<char>(in)), {});
    las[104] = static_cast<char>(las[104] | 0x80);
    std::ofstream(dir_.file("in.laz"), std::ios::binary) << las;
  }
  EXPECT_NE(run(dir_.file("in.laz") + " " + dir_.file("o.pcd"), out, dir_), 0);
  EXPECT_NE(out.find("no LASzip VLR"), std::string::npos) << out;
  EXPECT_NE(run(dir_.file("in.las") + " " + dir_.file("o.pcd") + " -origin 1,2", out, dir_), 0);
  EXPECT_NE(run(dir_.file("in.las") + " " + dir_.file("o.pcd") + " -classes 9", out, dir_), 0);
  EXPECT_NE(out.find("No point"), std::string::npos) << out;
  EXPECT_NE(run(dir_.file("in.las"), out, dir_), 0);  // no output named
  EXPECT_EQ(run("-h", out, dir_), 0);
}

// pcl_ls3d_info reports what the readers see; -json gives one object per file.
TEST_F(ConvertTool, InfoToolReportsCountsStripsAndErrors)
{
  const std::string info_tool = std::string(PCL_LS3D_TOOL_DIR) + "/pcl_ls3d_info";
  if (!fs::exists(info_tool))
    FAIL() << info_tool << " is not built";
  const auto runInfo = [&](const std::string& args, std::string& out) {
    return runProgram("pcl_ls3d_info", args, out, dir_);
  };
  std::string out;
  ASSERT_EQ(runInfo("-json " + dir_.file("in.las"), out), 0) << out;
  EXPECT_NE(out.find("\"point_source_ids\":{\"10\":100,\"11\":100,\"12\":100}"), std::string::npos) << out;
  EXPECT_NE(out.find("\"classes\":{\"2\":100,\"5\":100,\"6\":100}"), std::string::npos) << out;
  EXPECT_NE(out.find("\"points_loaded\":300"), std::string::npos) << out;
  EXPECT_NE(runInfo(dir_.file("in.las") + " -bogus", out), 0);
  EXPECT_NE(runInfo(dir_.file("none.las"), out), 0);
  EXPECT_NE(out.find("does not exist"), std::string::npos) << out;
}

// Bad input exits 1 as in every other tool (not 255 from `return -1`).
TEST_F(ConvertTool, BadInputExitsOne)
{
  if (!fs::exists(kInfoTool))
    FAIL() << kInfoTool << " is not built";
  std::string out;
  EXPECT_EQ(run(dir_.file("missing.las") + " " + dir_.file("o.pcd"), out, dir_), 1) << out;
  EXPECT_EQ(run(dir_.file("in.las") + " " + dir_.file("o.pcd") + " -bogus", out, dir_), 1) << out;
  EXPECT_EQ(runInfo(dir_.file("none.las"), out, dir_), 1) << out;
  EXPECT_EQ(runInfo(dir_.file("in.las") + " -bogus", out, dir_), 1) << out;
}

// Several files with a bad one among them: every good file is still described, the bad one
// gets one error line, and the exit status says that one failed.
TEST_F(ConvertTool, InfoReportsEveryFile)
{
  if (!fs::exists(kInfoTool))
    FAIL() << kInfoTool << " is not built";
  {
    std::ofstream bad(dir_.file("bad.las"));
    bad << "not a LAS file\n";
  }
  std::string out;
  EXPECT_EQ(runInfo(dir_.file("in.las") + " " + dir_.file("bad.las") + " " + dir_.file("in.las"), out, dir_),
            1)
      << out;
  EXPECT_EQ(occurrences(out, "points in file 300, loaded 300"), 2u) << out;
  EXPECT_EQ(occurrences(out, "bad.las"), 1u) << out;
}

// A SEGMENTS.pcd's labels are segment ids, not classes: its segments are counted (ids above
// 255 too, which a byte-sized class would wrap) and no class histogram is printed.
TEST_F(ConvertTool, InfoCountsSegmentsOfASegmentsFile)
{
  if (!fs::exists(kInfoTool))
    FAIL() << kInfoTool << " is not built";
  pcl::PointCloud<pcl::PointXYZ> xyz;
  for (const auto& p : cloud_)
    xyz.push_back(pcl::PointXYZ(p.x, p.y, p.z));
  std::vector<pcl::PointIndices> segments(260);  // one point each; 40 points in none
  for (std::size_t s = 0; s < segments.size(); ++s)
    segments[s].indices = {static_cast<int>(s)};
  evaluation::InputLayout layout;
  layout.points_in_file = xyz.size();
  layout.origin = origin_;
  std::string error;
  ASSERT_TRUE(evaluation::saveSegmentsPcd(dir_.file("SEGMENTS.pcd"), xyz, segments, layout, error)) << error;
  std::string out;
  ASSERT_EQ(runInfo(dir_.file("SEGMENTS.pcd"), out, dir_), 0) << out;
  EXPECT_NE(out.find("segment ids"), std::string::npos) << out;
  EXPECT_NE(out.find("260 segments, 40 points in none"), std::string::npos) << out;
  EXPECT_EQ(out.find("\n  classes:"), std::string::npos) << out;  // no histogram line
  ASSERT_EQ(runInfo("-json " + dir_.file("SEGMENTS.pcd"), out, dir_), 0) << out;
  EXPECT_NE(out.find("\"segments\":{\"count\":260,\"points_in_none\":40}"), std::string::npos) << out;
  EXPECT_EQ(out.find("\"classes\""), std::string::npos) << out;
}

// pcl_ls3d_segment writes local float coordinates and keeps the origin in a header comment
// (segments_file.h). Info gives the box in the LAS input's frame, not the local one (which
// started near 0), and says the origin was applied.
TEST_F(ConvertTool, InfoGivesASegmentsFileBoxInTheInputFrame)
{
  if (!fs::exists(kInfoTool))
    FAIL() << kInfoTool << " is not built";
  std::string out;
  const std::string seg = segmentsFile();
  ASSERT_FALSE(HasFailure());
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const auto& p : cloud_) {
    lo = lo.cwiseMin(p.getVector3fMap().cast<double>() + origin_);
    hi = hi.cwiseMax(p.getVector3fMap().cast<double>() + origin_);
  }
  ASSERT_EQ(runInfo("-json " + seg, out, dir_), 0) << out;
  const nlohmann::json j = nlohmann::json::parse(out);
  ASSERT_TRUE(j.contains("origin_applied")) << out;
  EXPECT_GT(j["origin_applied"][0].get<double>(), 1e5) << out;
  for (int k = 0; k < 3; ++k) {
    // Floats within 400 m of the origin hold ~3e-5; the LAS file holds millimetres.
    EXPECT_NEAR(j["min"][k].get<double>(), lo[k], 2e-3) << k << " " << out;
    EXPECT_NEAR(j["max"][k].get<double>(), hi[k], 2e-3) << k << " " << out;
  }
  ASSERT_EQ(runInfo(seg, out, dir_), 0) << out;
  EXPECT_NE(out.find("applied (local float coordinates in the file)"), std::string::npos) << out;
  EXPECT_EQ(out.find("local origin"), std::string::npos) << out;  // said once, not twice
  const std::size_t at = out.find("bounds min ");
  ASSERT_NE(at, std::string::npos) << out;
  Eigen::Vector3d text_lo;
  ASSERT_EQ(std::sscanf(out.c_str() + at, "bounds min %lf %lf %lf", &text_lo[0], &text_lo[1], &text_lo[2]),
            3);
  EXPECT_LT((text_lo - lo).cwiseAbs().maxCoeff(), 2e-3) << out;

  // A file without a recorded origin is reported as it is, and says nothing of one.
  ASSERT_EQ(runInfo(dir_.file("in.las"), out, dir_), 0) << out;
  EXPECT_EQ(out.find("applied"), std::string::npos) << out;
}

// A SEGMENTS.pcd is read by loadCloud in the frame of the LAS it was made from, as that LAS is:
// its floats are the local coordinates and the recorded origin is the origin, so that every tool
// sees the projected coordinates (before, the origin was 0 and the points sat near (0, 0, 0)).
TEST_F(ConvertTool, SegmentsFileLoadsInTheInputFrame)
{
  const std::string seg = segmentsFile();
  ASSERT_FALSE(HasFailure());
  Eigen::Vector3d recorded;
  ASSERT_TRUE(recordedOrigin(seg, recorded));
  const std::vector<Eigen::Vector3d> las = rawLasCoordinates(dir_.file("in.las"));
  ASSERT_EQ(las.size(), cloud_.size());

  pcl::PointCloud<PointLiDAR> loaded;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(io::loadCloud(seg, loaded, info, error)) << error;
  EXPECT_EQ(info.origin, recorded);
  ASSERT_EQ(loaded.size(), las.size());       // every point finite: input order, one for one
  pcl::PointCloud<pcl::PointXYZRGBL> stored;  // what plain PCL reads
  ASSERT_EQ(pcl::io::loadPCDFile(seg, stored), 0);
  ASSERT_EQ(stored.size(), las.size());
  std::size_t changed = 0, off = 0;  // counted: one failure line, not one per point
  for (std::size_t i = 0; i < las.size(); ++i) {
    changed += loaded[i].getVector3fMap() != stored[i].getVector3fMap();
    const Eigen::Vector3d local = loaded[i].getVector3fMap().cast<double>();
    for (int k = 0; k < 3; ++k) {
      // The floats' rounding: half a step, at most 3e-5 within 400 m.
      const double tolerance = std::max(std::abs(local[k]), 1.0) * std::numeric_limits<float>::epsilon();
      if (!(std::abs(local[k] + info.origin[k] - las[i][k]) <= tolerance) && off++ == 0)
        ADD_FAILURE() << "point " << i << " axis " << k << ": " << local[k] + info.origin[k] << " loaded, "
                      << las[i][k] << " in the LAS";
    }
  }
  EXPECT_EQ(changed, 0u) << "points whose loaded floats differ from the stored ones";
  EXPECT_EQ(off, 0u) << "coordinates off, of " << 3 * las.size();
}

// pcl_ls3d_convert SEGMENTS.pcd out.las writes the projected coordinates, not the local ones.
TEST_F(ConvertTool, SegmentsFileConvertsToLasInTheInputFrame)
{
  std::string out;
  const std::string seg = segmentsFile();
  ASSERT_FALSE(HasFailure());
  ASSERT_EQ(run(seg + " " + dir_.file("out.las"), out, dir_), 0) << out;
  EXPECT_NE(out.find("Local origin (recorded in the file)"), std::string::npos) << out;
  const std::vector<Eigen::Vector3d> in = rawLasCoordinates(dir_.file("in.las"));
  const std::vector<Eigen::Vector3d> back = rawLasCoordinates(dir_.file("out.las"));
  ASSERT_EQ(back.size(), in.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < in.size(); ++i)
    worst = std::max(worst, (back[i] - in[i]).cwiseAbs().maxCoeff());
  EXPECT_LT(worst, 2e-3);  // float rounding 3e-5 and the 1 mm LAS quantum
}

// A SEGMENTS.pcd of IMRG gives the LAS its objects' classes; one of MRG names none, and its
// segment ids (which the reader would clamp into the classification byte) are not passed off
// as classes: classification 0 and a warning.
TEST_F(ConvertTool, SegmentsFileGivesObjectClassesNeverSegmentIds)
{
  const std::string seg = segmentsFile(), mrg = dir_.file("MRG.pcd");
  ASSERT_FALSE(HasFailure());
  std::string out;
  ASSERT_EQ(runProgram("pcl_ls3d_segment", dir_.file("in.las") + " -mode mrg -o " + mrg, out, dir_), 0)
      << out;
  const std::set<int> object_codes = {1, 2, 5, 6, 14, 15, 64};
  for (const auto& [file, expect_classes] : {std::pair{seg, true}, std::pair{mrg, false}}) {
    const std::string las = file + ".las";
    ASSERT_EQ(run(file + " " + las, out, dir_), 0) << out;
    EXPECT_EQ(out.find("holds segment ids") != std::string::npos, !expect_classes) << out;
    pcl::PointCloud<PointLiDAR> back;
    io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(io::loadCloud(las, back, info, error)) << error;
    std::set<int> codes;
    for (const auto& p : back)
      codes.insert(p.classification);
    if (expect_classes) {
      EXPECT_TRUE(std::includes(object_codes.begin(), object_codes.end(), codes.begin(), codes.end()))
          << *codes.begin() << " .. " << *codes.rbegin();
    } else {
      EXPECT_EQ(codes, std::set<int>{0});
    }
  }
}

// The CRS goes with the points: a LAS's into the header of a PCD (binary, ASCII, one per strip),
// which every pcl_ls3d reader gives back and plain PCL still loads, and from that PCD into a LAS.
// Before, a LAS converted to PCD lost its CRS, and with it the tools' unit and degree checks.
TEST_F(ConvertTool, CrsGoesWithThePoints)
{
  const std::string wkt = maps::crsFromUserInput("EPSG:32632");  // WGS 84 / UTM 32N
  io::SaveOptions with_crs;
  maps::recordCrs(wkt, with_crs);  // a WKT VLR in a LAS 1.4
  std::string error, out;
  ASSERT_TRUE(io::saveCloud(dir_.file("utm.las"), cloud_, origin_, error, with_crs)) << error;
  ASSERT_EQ(run(dir_.file("utm.las") + " " + dir_.file("b.pcd"), out, dir_), 0) << out;
  ASSERT_EQ(run(dir_.file("utm.las") + " " + dir_.file("a.pcd") + " -ascii", out, dir_), 0) << out;
  ASSERT_EQ(run(dir_.file("utm.las") + " -split_strips " + dir_.file("strips") + " -format pcd", out, dir_),
            0)
      << out;
  ASSERT_EQ(run(dir_.file("b.pcd") + " " + dir_.file("back.las"), out, dir_), 0) << out;
  ASSERT_EQ(run(dir_.file("utm.las") + " " + dir_.file("copy.las"), out, dir_), 0) << out;
  ASSERT_EQ(run(dir_.file("utm.las") + " " + dir_.file("b.ply"), out, dir_), 0) << out;
  ASSERT_EQ(run(dir_.file("utm.las") + " " + dir_.file("a.ply") + " -ascii", out, dir_), 0) << out;
  ASSERT_EQ(run(dir_.file("b.ply") + " " + dir_.file("back_ply.las"), out, dir_), 0) << out;
  for (const std::string name : {"back.las", "copy.las"}) {  // one CRS record, in a LAS 1.4
    SCOPED_TRACE(name);
    pcl::PointCloud<PointLiDAR> c;
    io::CloudInfo info;
    ASSERT_TRUE(io::loadCloud(dir_.file(name), c, info, error)) << error;
    EXPECT_EQ(info.las.version_minor, 4);
    EXPECT_EQ(std::count_if(info.las.vlrs.begin(), info.las.vlrs.end(),
                            [](const io::LasVlr& v) { return v.record_id == 2112; }),
              1);
  }
  for (const std::string name :
       {"b.pcd", "a.pcd", "strips/utm_psid11.pcd", "back.las", "b.ply", "a.ply", "back_ply.las"}) {
    SCOPED_TRACE(name);
    pcl::PointCloud<PointLiDAR> c;
    io::CloudInfo info;
    ASSERT_TRUE(io::loadCloud(dir_.file(name), c, info, error)) << error;
    ASSERT_EQ(c.size(), name.find("strips") == 0 ? cloud_.size() / 3 : cloud_.size());
    EXPECT_TRUE(maps::sameCrs(maps::crsOfFile(info), wkt)) << maps::crsOfFile(info);
    if (name.find("strips") != 0) {  // the points themselves, to the LAS millimetre
      EXPECT_LT(((c[7].getVector3fMap().cast<double>() + info.origin) -
                 (cloud_[7].getVector3fMap().cast<double>() + origin_))
                    .norm(),
                2e-3);
    }
  }
  // PCL's own readers take the files with their CRS line as they are.
  pcl::PCLPointCloud2 plain, plain_ply;
  ASSERT_EQ(pcl::io::loadPCDFile(dir_.file("b.pcd"), plain), 0);
  EXPECT_EQ(plain.width * plain.height, cloud_.size());
  ASSERT_EQ(pcl::io::loadPLYFile(dir_.file("b.ply"), plain_ply), 0);
  EXPECT_EQ(plain_ply.width * plain_ply.height, cloud_.size());
  // Without a CRS in the input, none is invented.
  ASSERT_EQ(run(dir_.file("in.las") + " " + dir_.file("none.pcd"), out, dir_), 0) << out;
  pcl::PointCloud<PointLiDAR> c;
  io::CloudInfo info;
  ASSERT_TRUE(io::loadCloud(dir_.file("none.pcd"), c, info, error)) << error;
  EXPECT_TRUE(info.file_crs_wkt.empty()) << info.file_crs_wkt;
}
