/// \file test_hostile_files.cpp
/// \brief Issue 12: no reader trusts a header count. Crafted PCD/PLY headers that claim far more
///        than the file holds fail with one line naming the claim; a 10 MB line of XYZ garbage
///        gives a short error with line and column; a Stanford range_grid is not "dropped points".

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/pcd_io.h>
#include <pcl_ls3d/io/ply_io.h>

#include "io/hostile_files.h"
#include "io/io_test_utils.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

using namespace pcl_ls3d;
using pcl_ls3d_test::TempDir;

namespace {

void
writeFile(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary) << bytes;
}

/// A Stanford scanner PLY: a 4 x 3 range grid (obj_info num_cols / num_rows) around 6 vertices;
/// grid cells list the vertex they hold (count 1) or none (count 0).
std::string
stanfordPly(const std::string& cols, const std::string& rows)
{
  std::string s = "ply\nformat ascii 1.0\nobj_info is_cyberware_data 1\nobj_info is_mesh 0\n"
                  "obj_info num_cols " +
                  cols + "\nobj_info num_rows " + rows +
                  "\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
                  "element range_grid 12\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < 6; ++i)
    s += std::to_string(0.01 * i) + " " + std::to_string(0.02 * i) + " -0.1\n";
  for (int cell = 0; cell < 12; ++cell)
    s += cell % 2 == 0 ? "1 " + std::to_string(cell / 2) + "\n" : "0\n";
  return s;
}

}  // namespace

// Every crafted header (a billion points in a 10-point PCD, a negative or 2^32 - 1 PLY vertex
// count, ...) fails through loadCloud with one line that names the file and the false claim.
TEST(HostileFiles, HeaderCountsAreCheckedAgainstTheData)
{
  TempDir dir("ls3d_hostile");
  for (const auto& f : pcl_ls3d_test::hostileFiles()) {
    SCOPED_TRACE(f.name);
    writeFile(dir.file(f.name), f.bytes);
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    EXPECT_FALSE(io::loadCloud(dir.file(f.name), cloud, info, error));
    EXPECT_NE(error.find(f.expect), std::string::npos) << error;
    EXPECT_NE(error.find(f.name), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_LT(error.size(), 300u) << error;
    EXPECT_TRUE(cloud.empty());
  }
}

// A single 10 MB line of garbage: the error quotes 40 characters, gives line and column and the
// token's length, and stays one short line.
TEST(HostileFiles, XyzGarbageIsQuotedShortWithLineAndColumn)
{
  TempDir dir("ls3d_hostile_xyz");
  std::string garbage(10000000, 'q');
  for (std::size_t i = 0; i < garbage.size(); i += 7)
    garbage[i] = static_cast<char>('A' + i % 26);
  writeFile(dir.file("garbage.xyz"), garbage + "\n");
  writeFile(dir.file("late.xyz"), "1 2 3\n4 5 " + garbage + "\n");
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  EXPECT_FALSE(io::loadCloud(dir.file("garbage.xyz"), cloud, info, error));
  EXPECT_NE(error.find("line 1, column 1: cannot parse 'Aqqqqqq"), std::string::npos) << error;
  EXPECT_NE(error.find("(10000000 characters)"), std::string::npos) << error;
  EXPECT_LT(error.size(), 200u);
  EXPECT_FALSE(io::loadCloud(dir.file("late.xyz"), cloud, info, error));
  EXPECT_NE(error.find("line 2, column 5: cannot parse"), std::string::npos) << error;
  EXPECT_LT(error.size(), 200u);
  EXPECT_EQ(error.find('\n'), std::string::npos);
}

// Bad binary_compressed blocks: a size block that disagrees with the header, a compressed size
// beyond the file, and LZF data that refers before its start.
TEST(HostileFiles, PcdCompressedBlocksAreChecked)
{
  const std::string header = pcl_ls3d_test::pcdHeader("2", "2", "binary_compressed");
  using pcl_ls3d_test::uint32Bytes;
  const std::pair<std::string, std::string> cases[] = {
      {header + uint32Bytes(4) + uint32Bytes(99) + "abcd", "size block says 99 bytes"},
      {header + uint32Bytes(1000) + uint32Bytes(24) + "abcd", "compressed block of 1000 bytes"},
      {header + uint32Bytes(3) + uint32Bytes(24) + std::string("\x20\x10\x00", 3), "corrupt"},
      {header + "abc", "shorter than its 8-byte size block"}};
  for (const auto& [bytes, expect] : cases) {
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    EXPECT_FALSE(
        io::readPcd(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), cloud, info, error));
    EXPECT_NE(error.find(expect), std::string::npos) << error;
  }
}

// PLY lists: a negative count (char) and a count running past the data are errors; the list
// items themselves are skipped.
TEST(HostileFiles, PlyListCountsAreChecked)
{
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
                             "property float x\nproperty float y\nproperty float z\n"
                             "property list char int ids\nend_header\n";
  const std::string xyz = pcl_ls3d_test::floatTriplets(2).substr(12, 12);
  const std::pair<std::string, std::string> cases[] = {
      {header + xyz + std::string(1, '\xff'), "list 'ids' count -1"},
      {header + xyz + std::string(1, '\x10') + "abcd", "list 'ids' count 16"},
      {header + xyz + std::string(1, '\x01') + "abcd", ""}};
  for (const auto& [bytes, expect] : cases) {
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    const bool ok =
        io::readPly(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), cloud, info, error);
    EXPECT_EQ(ok, expect.empty()) << error;
    EXPECT_NE(error.find(expect), std::string::npos) << error;
    if (ok) {
      EXPECT_EQ(cloud.size(), 1u);
    }
  }
}

// A Stanford range scan: 6 vertices in a 12-cell range_grid. The readers report 6 points in the
// file and none dropped (the grid is not read); an obj_info grid of 10^10 cells allocates nothing.
TEST(StanfordPly, RangeGridIsNotCountedAsDroppedPoints)
{
  TempDir dir("ls3d_stanford");
  writeFile(dir.file("scan.ply"), stanfordPly("4", "3"));
  writeFile(dir.file("huge_grid.ply"), stanfordPly("100000", "100000"));
  for (const char* name : {"scan.ply", "huge_grid.ply"}) {
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(io::loadCloud(dir.file(name), cloud, info, error)) << error;
    EXPECT_EQ(info.points_in_file, 6u);
    EXPECT_EQ(info.points_loaded, 6u);
    EXPECT_EQ(info.points_dropped_nonfinite, 0u);
    ASSERT_EQ(cloud.size(), 6u);
    EXPECT_FLOAT_EQ(cloud[5].x, 0.05f);
    EXPECT_FLOAT_EQ(cloud[5].y, 0.1f);
    EXPECT_FLOAT_EQ(cloud[5].z, -0.1f);
  }
}
