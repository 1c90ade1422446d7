/// \file test_las_broken.cpp
/// \brief Every kind of bad LAS input gets one clear error and no crash: each error kind on an
///        in-memory mutation of a valid file, the committed corpus (test/data/las_corpus, made by
///        fuzz/make_las_corpus.py) through loadCloud(), and random truncations/byte flips.

#include <pcl_ls3d/io/las_io.h>

#include "io/io_test_utils.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

using namespace pcl_ls3d;

namespace {

/// A valid LAS 1.<minor> file of 5 points in `format`.
std::vector<std::uint8_t>
validLas(int minor = 2, int format = 3)
{
  pcl::PointCloud<PointLiDAR> cloud;
  std::vector<Eigen::Vector3d> truth;
  pcl_ls3d_test::makeUtmCloud(5, format, {500100.0, 5000100.0, 50.0}, {500000.0, 5000000.0, 0.0}, cloud,
                              truth);
  io::SaveOptions so;
  so.las_minor_version = static_cast<std::uint8_t>(minor);
  so.las_point_format = static_cast<std::uint8_t>(format);
  std::vector<std::uint8_t> bytes;
  std::string error;
  io::writeLas(cloud, {500000.0, 5000000.0, 0.0}, bytes, error, so);
  return bytes;
}

template <typename T>
std::vector<std::uint8_t>
patched(std::vector<std::uint8_t> b, std::size_t offset, T v)
{
  std::memcpy(b.data() + offset, &v, sizeof(T));
  return b;
}

/// readLas must fail with an error containing `expected`.
void
expectError(const std::vector<std::uint8_t>& bytes, const std::string& expected)
{
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  EXPECT_FALSE(io::readLas(bytes.data(), bytes.size(), cloud, info, error)) << expected;
  EXPECT_NE(error.find(expected), std::string::npos) << "got: " << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
}

}  // namespace

TEST(LasBroken, ValidFileParses)
{
  const auto b = validLas();
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(io::readLas(b.data(), b.size(), cloud, info, error)) << error;
  EXPECT_EQ(cloud.size(), 5u);
}

TEST(LasBroken, EachErrorKindHasItsMessage)
{
  const auto b = validLas();
  const auto b14 = validLas(4, 6);
  expectError({}, "empty file");
  expectError(patched<char>(b, 3, 'X'), "signature");
  expectError({b.begin(), b.begin() + 200}, "truncated LAS header");
  expectError({b14.begin(), b14.begin() + 300}, "truncated LAS header");
  expectError({b.begin(), b.end() - 3}, "point block truncated");
  expectError(patched<std::uint32_t>(b, 107, 6), "point block truncated or point count wrong");
  expectError(patched<std::uint64_t>(b14, 247, ~0ull), "point count wrong");  // no huge allocation
  expectError(patched<std::uint32_t>(patched<std::uint64_t>(b14, 247, 5), 107, 4), "mismatch");
  expectError(patched<std::uint8_t>(b, 25, 5), "unsupported LAS version 1.5");
  expectError(patched<std::uint8_t>(b, 24, 2), "unsupported LAS version 2.2");
  expectError(patched<std::uint8_t>(b, 104, 11), "unsupported LAS point format 11");
  expectError(patched<std::uint16_t>(b, 105, 28), "smaller than the 34 bytes");
  expectError(patched<std::uint32_t>(b, 96, 1u << 30), "beyond the end of the file");
  expectError(patched<std::uint32_t>(b, 96, 100), "inside the 227-byte header");
  expectError(patched<std::uint16_t>(b14, 94, 235), "smaller than the 375 bytes");
  expectError(patched<std::uint8_t>(b, 104, 0x83), "compressed (LAZ), but the file has no LASzip VLR");
  expectError(patched<std::uint8_t>(b, 104, 0x43), "no LASzip VLR");
  expectError(patched<std::uint32_t>(b, 100, 1), "does not fit before the point data");
  expectError(patched<double>(b, 131, 0.0), "invalid scale factor");
  expectError(patched<std::uint32_t>(validLas(), 107, 0), "no points");
}

// A LASzip VLR marks the records compressed even when the format byte does not: this one (all
// zeros) names no compressor, so the file is refused.
TEST(LasBroken, LaszipVlrIsDetected)
{
  pcl::PointCloud<PointLiDAR> cloud;
  std::vector<Eigen::Vector3d> truth;
  pcl_ls3d_test::makeUtmCloud(3, 3, {0, 0, 0}, {0, 0, 0}, cloud, truth);
  io::SaveOptions so;
  so.las_vlrs.push_back({"laszip encoded", 22204, "", std::vector<std::uint8_t>(34, 0)});
  // The writer drops a LASzip VLR (its records are not compressed); patch one in by hand.
  so.las_vlrs[0].user_id = "laszip_encoded";
  std::vector<std::uint8_t> bytes;
  std::string error;
  ASSERT_TRUE(io::writeLas(cloud, Eigen::Vector3d::Zero(), bytes, error, so)) << error;
  bytes[227 + 2 + 6] = ' ';  // "laszip_encoded" -> "laszip encoded"
  expectError(bytes, "the LASzip VLR names compressor 0");
}

// A file is read by its content: an uncompressed LAS file named .laz loads; a compression bit
// without its LASzip VLR is refused.
TEST(LasBroken, LazExtensionAndEmptyFileThroughLoadCloud)
{
  pcl_ls3d_test::TempDir dir("ls3d_las_broken");
  auto b = validLas();
  std::ofstream(dir.file("plain.laz"), std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), b.size());
  b[104] |= 0x80;
  std::ofstream(dir.file("a.laz"), std::ios::binary).write(reinterpret_cast<const char*>(b.data()), b.size());
  std::ofstream(dir.file("empty.las"));
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  EXPECT_TRUE(io::loadCloud(dir.file("plain.laz"), cloud, info, error)) << error;
  EXPECT_EQ(cloud.size(), 5u);
  EXPECT_FALSE(io::loadCloud(dir.file("a.laz"), cloud, info, error));
  EXPECT_NE(error.find("no LASzip VLR"), std::string::npos) << error;
  EXPECT_FALSE(io::loadCloud(dir.file("empty.las"), cloud, info, error));
  EXPECT_NE(error.find("empty file"), std::string::npos) << error;
  EXPECT_FALSE(io::loadCloud(dir.file("missing.las"), cloud, info, error));
  EXPECT_NE(error.find("does not exist"), std::string::npos) << error;
}

// Replays the committed broken corpus: every file must be refused with a one-line reason.
TEST(LasBroken, CommittedCorpusIsRejected)
{
  const std::filesystem::path dir = std::filesystem::path(PCL_LS3D_TEST_SOURCE_DIR) / "data" / "las_corpus";
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".las")
      continue;
    ++files;
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    EXPECT_FALSE(io::loadCloud(entry.path().string(), cloud, info, error)) << entry.path();
    EXPECT_FALSE(error.empty()) << entry.path();
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_TRUE(cloud.empty());
  }
  EXPECT_GE(files, 20);
}

// Every truncation of a valid file and a few thousand random byte flips either parse or fail
// cleanly (the libFuzzer target does this at scale under AddressSanitizer).
TEST(LasBroken, TruncationsAndByteFlipsNeverCrash)
{
  for (const auto& valid : {validLas(), validLas(4, 8)}) {
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    for (std::size_t len = 0; len < valid.size(); ++len) {
      const std::vector<std::uint8_t> cut(valid.begin(), valid.begin() + len);
      EXPECT_FALSE(io::readLas(cut.data(), cut.size(), cloud, info, error)) << len;
    }
    std::mt19937 rng(1);
    for (int trial = 0; trial < 3000; ++trial) {
      auto b = valid;
      for (int k = 0; k < 3; ++k)
        b[rng() % 260] = static_cast<std::uint8_t>(rng());
      if (!io::readLas(b.data(), b.size(), cloud, info, error)) {
        EXPECT_FALSE(error.empty());
      }
    }
  }
}
