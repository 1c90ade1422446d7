/// \file test_laz_hostile.cpp
/// \brief Bad LAZ input gets one clear error line, no crash, and memory bounded by the file's real
///        size: truncated files, a chunk table that is missing, corrupt or points outside the
///        file, counts the bytes cannot hold, a LASzip VLR naming unknown items or versions, a
///        .laz without a LASzip VLR, garbage in a chunk. Where the chunks can still be found (a
///        missing table with fixed-size chunks) the file decodes exactly, as LASzip does.

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/las_io.h>

#include "io/io_test_utils.h"
#include "io/laz_test_utils.h"
#include "io/memory_probe.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

using namespace pcl_ls3d;

namespace {

constexpr std::size_t kPoints = 5000;
constexpr std::uint32_t kChunk = 1000;

/// A valid LAZ file (PF3, 5000 points in 5 chunks of 1000) and the LAS file it compresses.
void
validLaz(std::vector<std::uint8_t>& las, std::vector<std::uint8_t>& laz, int minor = 2)
{
  pcl::PointCloud<PointLiDAR> cloud;
  std::vector<Eigen::Vector3d> truth;
  pcl_ls3d_test::makeUtmCloud(kPoints, 3, {500100.0, 5000100.0, 50.0}, {500000.0, 5000000.0, 0.0}, cloud,
                              truth);
  io::SaveOptions so;
  so.las_minor_version = static_cast<std::uint8_t>(minor);
  std::string error;
  ASSERT_TRUE(io::writeLas(cloud, {500000.0, 5000000.0, 0.0}, las, error, so)) << error;
  ASSERT_TRUE(io::compressLas(las.data(), las.size(), laz, error, kChunk)) << error;
}

template <typename T>
std::vector<std::uint8_t>
patched(std::vector<std::uint8_t> b, std::size_t offset, T v)
{
  std::memcpy(b.data() + offset, &v, sizeof(T));
  return b;
}

std::uint32_t
offsetToPoints(const std::vector<std::uint8_t>& b)
{
  std::uint32_t v;
  std::memcpy(&v, b.data() + 96, 4);
  return v;
}

std::int64_t
tableOffset(const std::vector<std::uint8_t>& b)
{
  std::int64_t v;
  std::memcpy(&v, b.data() + offsetToPoints(b), 8);
  return v;
}

/// Where the LASzip VLR's payload starts (it is the last VLR).
std::size_t
laszipPayload(const std::vector<std::uint8_t>& b)
{
  return offsetToPoints(b) - (34 + 6 * 3);  // PF3: POINT10, GPSTIME11, RGB12
}

/// readLas() on the bytes, and loadCloud() on them written to a .laz file (what every tool
/// calls), must refuse with one line containing `expected`.
void
expectError(const std::vector<std::uint8_t>& bytes, const std::string& expected,
            const io::LoadOptions& options = {})
{
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  EXPECT_FALSE(io::readLas(bytes.data(), bytes.size(), cloud, info, error, options)) << expected;
  EXPECT_NE(error.find(expected), std::string::npos) << "got: " << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
  pcl_ls3d_test::TempDir dir("ls3d_laz_hostile_load");
  const std::string path = dir.file("hostile.laz");
  pcl_ls3d_test::writeBytes(path, bytes);
  std::string load_error;
  EXPECT_FALSE(io::loadCloud(path, cloud, info, load_error, options)) << expected;
  EXPECT_EQ(load_error, path + ": " + error);
}

/// decompressLaz() must give back exactly `las` (the chunks found without the table).
void
expectDecodes(const std::vector<std::uint8_t>& laz, const std::vector<std::uint8_t>& las, bool with_table)
{
  std::vector<std::uint8_t> back;
  std::string error;
  ASSERT_TRUE(io::decompressLaz(laz.data(), laz.size(), back, error)) << error;
  io::LasHeaderInfo h1, h2;
  EXPECT_EQ(pcl_ls3d_test::lasRecords(back, h1), pcl_ls3d_test::lasRecords(las, h2));
  io::LasHeaderInfo h;
  ASSERT_TRUE(io::readLasHeader(laz.data(), laz.size(), h, error)) << error;
  EXPECT_EQ(h.laz.chunk_table, with_table);
}

}  // namespace

TEST(LazHostile, TruncatedFilesAreRefusedWithOneLine)
{
  std::vector<std::uint8_t> las, laz;
  validLaz(las, laz);
  std::size_t refused = 0;
  for (std::size_t cut = 0; cut < laz.size(); cut += 97) {
    const std::vector<std::uint8_t> part(laz.begin(), laz.begin() + cut);
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    const bool loaded = io::readLas(part.data(), part.size(), cloud, info, error);
    if (cut >= static_cast<std::size_t>(tableOffset(laz))) {
      // Only the chunk table is cut: the chunks are walked, every point is there.
      EXPECT_TRUE(loaded && cloud.size() == kPoints) << error;
      continue;
    }
    if (loaded) {
      ADD_FAILURE() << "a file cut at byte " << cut << " of " << laz.size() << " loaded";
      continue;
    }
    ++refused;
    EXPECT_FALSE(error.empty());
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
  EXPECT_GT(refused, 100u);
  // Cut inside the chunks (the table then lies outside the file): the chunks are walked and the
  // first one missing bytes is named.
  const std::vector<std::uint8_t> half(laz.begin(), laz.begin() + laz.size() / 2);
  expectError(half, "chunk 3 of 5");
}

TEST(LazHostile, MissingChunkTableIsWalkedAround)
{
  std::vector<std::uint8_t> las, laz;
  validLaz(las, laz);
  const std::size_t pointer = offsetToPoints(laz);
  expectDecodes(laz, las, true);
  // The writer stopped before writing the table: the offset points at itself.
  expectDecodes(patched<std::int64_t>(laz, pointer, static_cast<std::int64_t>(pointer)), las, false);
  // The offset is -1 (written to a stream) but the file does not end with the table's offset.
  expectDecodes(patched<std::int64_t>(laz, pointer, -1), las, false);
  // The offset points beyond the file, or into the header.
  expectDecodes(patched<std::int64_t>(laz, pointer, 1ll << 40), las, false);
  expectDecodes(patched<std::int64_t>(laz, pointer, 100), las, false);
  // The table is cut off.
  const std::vector<std::uint8_t> no_table(laz.begin(), laz.begin() + tableOffset(laz));
  expectDecodes(no_table, las, false);
  // -1 with the offset at the end of the file, as a streaming writer leaves it.
  std::vector<std::uint8_t> streamed = patched<std::int64_t>(laz, pointer, -1);
  const std::int64_t at = tableOffset(laz);
  streamed.insert(streamed.end(), reinterpret_cast<const std::uint8_t*>(&at),
                  reinterpret_cast<const std::uint8_t*>(&at) + 8);
  expectDecodes(streamed, las, true);
}

TEST(LazHostile, CorruptChunkTables)
{
  std::vector<std::uint8_t> las, laz;
  validLaz(las, laz);
  const std::size_t table = static_cast<std::size_t>(tableOffset(laz));
  // Unusable tables (wrong version, a count the bytes cannot hold, fewer chunks than the points
  // need): fixed-size chunks are walked.
  expectDecodes(patched<std::uint32_t>(laz, table, 3), las, false);
  expectDecodes(patched<std::uint32_t>(laz, table + 4, 4000000000u), las, false);
  expectDecodes(patched<std::uint32_t>(laz, table + 4, 2), las, false);
  // A table whose entries are garbage: either its chunks run past it (walked) or a chunk's
  // bytes disagree with what its points take (refused, naming the chunk).
  std::mt19937 rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::uint8_t> bad = laz;
    for (std::size_t i = table + 8; i < bad.size(); ++i)
      bad[i] = static_cast<std::uint8_t>(rng());
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    if (!io::readLas(bad.data(), bad.size(), cloud, info, error)) {
      EXPECT_NE(error.find("chunk"), std::string::npos) << error;
      EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    } else {
      EXPECT_EQ(cloud.size(), kPoints);
    }
  }
}

TEST(LazHostile, VariableChunksWithoutTableAreRefused)
{
  std::vector<std::uint8_t> las, laz;
  validLaz(las, laz);
  std::vector<std::uint8_t> bad = patched<std::uint32_t>(laz, laszipPayload(laz) + 12, 0xFFFFFFFFu);
  bad = patched<std::int64_t>(bad, offsetToPoints(bad), static_cast<std::int64_t>(1) << 40);
  expectError(bad, "chunks of varying size cannot be found without it");
}

TEST(LazHostile, CountsBeyondTheFile)
{
  std::vector<std::uint8_t> las, laz;
  validLaz(las, laz);
  // The header claims far more points than the chunks hold or the bytes could.
  expectError(patched<std::uint32_t>(laz, 107, 4000000000u), "more than the");
  // One point more than the chunks hold: a sixth chunk, which has no bytes.
  expectError(patched<std::uint32_t>(laz, 107, kPoints + 1), "chunk 6 of 6");
  // LAS 1.4: a 64-bit count of 2^60.
  std::vector<std::uint8_t> las14, laz14;
  validLaz(las14, laz14, 4);
  expectError(patched<std::uint64_t>(patched<std::uint32_t>(laz14, 107, 0), 247, 1ull << 60),
              "more than the");
  // The chunk table offset in the header's point data offset beyond the file.
  expectError(patched<std::uint32_t>(laz, 96, 1u << 30), "beyond the end of the file");
  // EVLRs beyond the file.
  expectError(patched<std::uint32_t>(patched<std::uint64_t>(laz14, 235, 1ull << 50), 243, 1),
              "runs past the end of the file");
}

TEST(LazHostile, UnknownItemsVersionsAndCompressors)
{
  std::vector<std::uint8_t> las, laz;
  validLaz(las, laz);
  const std::size_t vlr = laszipPayload(laz);
  expectError(patched<std::uint16_t>(laz, vlr, 7), "compressor 7");
  expectError(patched<std::uint16_t>(laz, vlr + 2, 1), "coder 1");
  expectError(patched<std::uint16_t>(laz, vlr + 34, 99), "item type 99");
  expectError(patched<std::uint16_t>(laz, vlr + 34 + 4, 9), "version 9");
  expectError(patched<std::uint16_t>(laz, vlr + 34 + 6 + 2, 9), "items cover");
  expectError(patched<std::uint16_t>(laz, vlr + 32, 60), "declares 60 items");
  expectError(patched<std::uint16_t>(laz, vlr + 34 + 12, 9), "waveform");  // RGB12 -> WAVEPACKET13
}

TEST(LazHostile, CompressionBitWithoutLaszipVlr)
{
  std::vector<std::uint8_t> las, laz;
  validLaz(las, laz);
  expectError(patched<std::uint8_t>(las, 104, 0x83), "no LASzip VLR");
  expectError(patched<std::uint8_t>(las, 104, 0x43), "LAZ");
}

TEST(LazHostile, GarbageInAChunkIsRefusedNamingIt)
{
  std::vector<std::uint8_t> las, laz;
  validLaz(las, laz);
  std::mt19937 rng(2);
  const std::size_t begin = offsetToPoints(laz) + 8;
  const std::size_t end = static_cast<std::size_t>(tableOffset(laz));
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<std::uint8_t> bad = laz;
    const std::size_t at = begin + 34 + rng() % (end - begin - 64);
    for (std::size_t i = at; i < at + 16; ++i)
      bad[i] = static_cast<std::uint8_t>(rng());
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    // A changed byte may also just decode to other values (an arithmetic code has no checksum);
    // it must never crash, and a refusal names the chunk.
    if (!io::readLas(bad.data(), bad.size(), cloud, info, error)) {
      EXPECT_NE(error.find("chunk"), std::string::npos) << error;
      EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    }
  }
  // Zeros over a whole chunk's stream: it can no longer end where the table says.
  std::vector<std::uint8_t> zeroed = laz;
  std::fill(zeroed.begin() + begin + 34, zeroed.begin() + begin + 2000, 0);
  expectError(zeroed, "chunk 1 of 5");
}

// Hostile files cost little memory: the load runs in a child with its address space capped.
TEST(LazHostile, MemoryStaysBounded)
{
  pcl_ls3d_test::TempDir dir("ls3d_laz_hostile");
  std::vector<std::uint8_t> las, laz, las14, laz14;
  validLaz(las, laz);
  validLaz(las14, laz14, 4);
  const std::vector<std::pair<std::string, std::vector<std::uint8_t>>> files = {
      {"huge_count.laz", patched<std::uint32_t>(laz, 107, 4000000000u)},
      {"huge_count14.laz", patched<std::uint64_t>(patched<std::uint32_t>(laz14, 107, 0), 247, 1ull << 60)},
      {"huge_chunk.laz", patched<std::uint32_t>(patched<std::uint32_t>(laz, 107, 4000000000u),
                                                laszipPayload(laz) + 12, 4000000000u)},
      {"huge_table.laz",
       patched<std::uint32_t>(laz, static_cast<std::size_t>(tableOffset(laz)) + 4, 4000000000u)},
  };
  for (const auto& f : files) {
    SCOPED_TRACE(f.first);
    pcl_ls3d_test::writeBytes(dir.file(f.first), f.second);
    const auto r = pcl_ls3d_test::probeLoad(dir.file(f.first), 512);
    ASSERT_TRUE(r.child_ok) << "the load crashed or hit the allocation cap";
    EXPECT_LT(r.peak_growth_kb, 32768) << "peak RSS growth " << r.peak_growth_kb << " KiB";
  }
}

namespace {

/// simple.copc.laz (laspy) with its hierarchy patched: the root page's place, and entry `e` of
/// the root page (32 bytes: key, offset, byte size, point count).
struct CopcFile
{
  std::vector<std::uint8_t> bytes;
  std::size_t info = 0;  // the COPC info VLR's payload

  bool
  load()
  {
    bytes = pcl_ls3d_test::readBytes(pcl_ls3d_test::sharedData("laz/laspy/simple.copc.laz"));
    if (bytes.size() < 400)
      return false;
    std::uint16_t header;
    std::memcpy(&header, bytes.data() + 94, 2);
    info = header + 54u;  // COPC requires its info VLR first
    return std::string(reinterpret_cast<const char*>(bytes.data()) + header + 2, 4) == "copc";
  }
  std::uint64_t
  rootOffset() const
  {
    std::uint64_t v;
    std::memcpy(&v, bytes.data() + info + 40, 8);
    return v;
  }
  std::uint64_t
  rootSize() const
  {
    std::uint64_t v;
    std::memcpy(&v, bytes.data() + info + 48, 8);
    return v;
  }
  std::size_t
  entry(std::size_t e) const
  {
    return static_cast<std::size_t>(rootOffset()) + 32 * e;
  }
};

}  // namespace

// COPC hierarchies that point outside the file or into a loop, keys outside the octree, counts
// beyond the header, and nodes whose bytes or counts are wrong: one line through loadCloud, a
// full load and a box query alike, with memory bounded.
TEST(LazHostile, CopcHierarchiesAreRefusedThroughLoadCloud)
{
  CopcFile f;
  if (!f.load())
    GTEST_SKIP() << "shared data not found: laz/laspy/simple.copc.laz";
  io::LoadOptions query;
  io::Region box;
  box.box = Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-1e9), Eigen::Vector3d::Constant(1e9));
  query.region = box;
  {  // the intact file loads, both ways
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(io::readLas(f.bytes.data(), f.bytes.size(), cloud, info, error, query)) << error;
    ASSERT_TRUE(info.region.copc);
    ASSERT_EQ(cloud.size(), info.las.point_count);
  }
  const std::size_t e0 = f.entry(0);
  std::int32_t size0, count0;
  std::memcpy(&size0, f.bytes.data() + e0 + 24, 4);
  std::memcpy(&count0, f.bytes.data() + e0 + 28, 4);
  std::uint64_t offset0;
  std::memcpy(&offset0, f.bytes.data() + e0 + 16, 8);
  ASSERT_GT(count0, 0) << "the root page's first entry is a node with points";
  pcl_ls3d_test::TempDir dir("ls3d_copc_hostile");
  struct Case
  {
    const char* name;
    std::vector<std::uint8_t> bytes;
    const char* expect;
    bool query_only;  // the hierarchy is sound; only decoding the node shows the damage
  };
  std::vector<std::uint8_t> loop = patched<std::int32_t>(f.bytes, e0 + 28, -1);
  loop = patched<std::uint64_t>(loop, e0 + 16, f.rootOffset());
  loop = patched<std::int32_t>(loop, e0 + 24, static_cast<std::int32_t>(f.rootSize()));
  const std::vector<Case> cases = {
      {"root page beyond the file", patched<std::uint64_t>(f.bytes, f.info + 40, f.bytes.size() + 64),
       "lies outside the file", false},
      {"root page of a partial entry", patched<std::uint64_t>(f.bytes, f.info + 48, f.rootSize() + 5),
       "not whole entries", false},
      {"a loop", loop, "referenced twice (a loop", false},
      {"a node beyond the file", patched<std::uint64_t>(f.bytes, e0 + 16, 1ull << 40),
       "points at bytes outside the file", false},
      {"a key outside the octree", patched<std::int32_t>(f.bytes, e0 + 4, 5), "outside the octree", false},
      {"more points than the header", patched<std::int32_t>(f.bytes, e0 + 28, 2000000000),
       "more points than the header", false},
      {"a node one byte short", patched<std::int32_t>(f.bytes, e0 + 24, size0 - 1), "COPC node 0-0-0-0",
       true},
      {"a node one byte late", patched<std::uint64_t>(f.bytes, e0 + 16, offset0 + 1), "COPC node 0-0-0-0",
       true},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    expectError(c.bytes, c.expect, query);
    if (!c.query_only) {
      expectError(c.bytes, c.expect);
      const std::string path = dir.file(std::string(c.name) + ".copc.laz");
      pcl_ls3d_test::writeBytes(path, c.bytes);
      const auto r = pcl_ls3d_test::probeLoad(path, 256);
      ASSERT_TRUE(r.child_ok) << "the load crashed or hit the allocation cap";
      EXPECT_FALSE(r.loaded);
      EXPECT_LT(r.peak_growth_kb, 32768) << "peak RSS growth " << r.peak_growth_kb << " KiB";
    }
  }
}
