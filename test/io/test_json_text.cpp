/// \file test_json_text.cpp
/// \brief Issue 12 point 3: every JSON writer goes through io::toJsonText(), which writes bytes
///        that are not UTF-8 as U+FFFD instead of throwing; the tools that put file names or LAS
///        header strings into JSON (info, compare, segment) write valid JSON for a Latin-1 file
///        name and a LAS header with non-UTF-8 identifiers. Also issue 10 point 7: info and
///        convert report a Stanford range_grid scan without "dropped" points.

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/json_text.h>

#include "io/io_test_utils.h"
#include "io/tool_run.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace pcl_ls3d;
using nlohmann::json;
using pcl_ls3d_test::runTool;
using pcl_ls3d_test::TempDir;

namespace {

const std::string kReplacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

/// A small wavy surface written as LAS, PCD or XYZ (by extension).
void
writeSurface(const std::string& path)
{
  pcl::PointCloud<PointLiDAR> cloud;
  for (int i = 0; i < 25; ++i)
    for (int j = 0; j < 25; ++j)
      cloud.push_back(PointLiDAR(static_cast<float>(i), static_cast<float>(j),
                                 static_cast<float>(std::sin(i / 3.0) + 0.1 * j)));
  std::string error;
  ASSERT_TRUE(io::saveCloud(path, cloud, Eigen::Vector3d::Zero(), error)) << error;
}

/// Overwrites a 32-byte LAS header string at `offset` with `text` padded with NULs.
void
patch(const std::string& path, std::size_t offset, std::string text)
{
  text.resize(32, '\0');
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>(offset));
  f.write(text.data(), static_cast<std::streamsize>(text.size()));
}

}  // namespace

TEST(JsonText, InvalidUtf8IsReplacedNotThrown)
{
  json j;
  j["name"] = std::string("caf\xE9 \xFF\xFE");
  j["ok"] = "caf\xC3\xA9";
  EXPECT_THROW(j.dump(), json::type_error);  // what every tool did before
  const std::string text = io::toJsonText(j);
  EXPECT_EQ(json::parse(text)["name"], "caf" + kReplacement + " " + kReplacement + kReplacement);
  EXPECT_EQ(json::parse(text)["ok"], "caf\xC3\xA9");
  EXPECT_EQ(io::toJsonText(j, 2), j.dump(2, ' ', false, json::error_handler_t::replace));
}

// pcl_ls3d_info -json on "caf\xE9.las" whose system identifier and generating software hold
// Latin-1 and 0xFF bytes: exit 0 and valid JSON (it aborted with type_error 316 before).
TEST(JsonText, InfoWritesValidJsonForNonUtf8LasHeaderAndFileName)
{
  TempDir dir("ls3d_json_info");
  const std::string path = dir.file("caf\xE9.las");
  writeSurface(path);
  patch(path, 26, std::string("Syst\xE8me \xFF\xFE", 10));  // system identifier (32 bytes)
  patch(path, 58, std::string("G\xE9n\xE9rateur", 10));     // generating software (32 bytes)
  const auto r = runTool("pcl_ls3d_info", "-json '" + path + "'", dir.path.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["file"], dir.file("caf" + kReplacement + ".las"));
  EXPECT_EQ(j["las"]["system_identifier"], "Syst" + kReplacement + "me " + kReplacement + kReplacement);
  EXPECT_EQ(j["las"]["generating_software"], "G" + kReplacement + "n" + kReplacement + "rateur");
  EXPECT_EQ(j["points_loaded"], 625);
}

// pcl_ls3d_compare and pcl_ls3d_segment put the input names into their reports.
TEST(JsonText, CompareAndSegmentWriteValidJsonForANonUtf8FileName)
{
  TempDir dir("ls3d_json_tools");
  const std::string input = dir.file("r\xE9sum\xE9.pcd");
  writeSurface(input);
  const auto c = runTool("pcl_ls3d_compare",
                         "'" + input + "' '" + input + "' -methods icp -json " + dir.file("compare.json"),
                         dir.path.string());
  ASSERT_EQ(c.code, 0) << c.out << c.err;
  const json jc = json::parse(pcl_ls3d_test::slurp(dir.file("compare.json")));
  EXPECT_NE(jc.dump().find("r" + kReplacement + "sum" + kReplacement + ".pcd"), std::string::npos);
  const auto s =
      runTool("pcl_ls3d_segment", "'" + input + "' -json " + dir.file("seg.json"), dir.path.string());
  ASSERT_EQ(s.code, 0) << s.out << s.err;
  const json js = json::parse(pcl_ls3d_test::slurp(dir.file("seg.json")));
  EXPECT_EQ(js["input"], dir.file("r" + kReplacement + "sum" + kReplacement + ".pcd"));
}

// A Stanford range scan (6 vertices in a 4 x 3 range_grid): info and convert say 6 points and
// report nothing dropped (PCL's reader laid the 12 grid cells out and 6 were counted as NaN).
TEST(StanfordPlyTools, InfoAndConvertDoNotReportGridCellsAsDropped)
{
  TempDir dir("ls3d_stanford_tools");
  std::string ply = "ply\nformat ascii 1.0\nobj_info num_cols 4\nobj_info num_rows 3\n"
                    "element vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
                    "element range_grid 12\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < 6; ++i)
    ply += std::to_string(i) + " " + std::to_string(2 * i) + " 1\n";
  for (int cell = 0; cell < 12; ++cell)
    ply += cell % 2 == 0 ? "1 " + std::to_string(cell / 2) + "\n" : "0\n";
  std::ofstream(dir.file("bun000.ply")) << ply;
  const auto info = runTool("pcl_ls3d_info", dir.file("bun000.ply"), dir.path.string());
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("points in file 6, loaded 6, NaN/inf dropped 0"), std::string::npos) << info.out;
  const auto conv =
      runTool("pcl_ls3d_convert", dir.file("bun000.ply") + " " + dir.file("b.pcd"), dir.path.string());
  ASSERT_EQ(conv.code, 0) << conv.err;
  EXPECT_NE(conv.out.find("(ply, 6 points)"), std::string::npos) << conv.out;
  EXPECT_EQ(conv.out.find("dropped"), std::string::npos) << conv.out;
}
