/// \file test_laz_roundtrip.cpp
/// \brief Generated records (no shared data needed) through the pointwise chunk coders and the
///        LAZ writer and reader: whatever is encoded decodes identical, for point formats 0–3
///        with and without extra bytes, item versions 1 and 2, chunk sizes down to 1 and a
///        partial last chunk; and a cloud saved as .laz loads as the same cloud saved as .las.

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/las_io.h>

#include "io/io_test_utils.h"
#include "io/laz/laszip_items.h"
#include "io/laz_test_utils.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

using namespace pcl_ls3d;
using namespace pcl_ls3d::io::laz;

namespace {

/// Plausible records of `format` with `extra` bytes: a scan line by line (small steps, returns
/// of a pulse together, times rising with occasional jumps and repeats, colours drifting), with
/// now and then a wild value (a far point, a time from another flight line, a random colour).
std::vector<std::uint8_t>
plausibleRecords(int format, std::size_t extra, std::size_t n, unsigned seed)
{
  const std::size_t base = io::lasPointRecordLength(format), length = base + extra;
  std::vector<std::uint8_t> out(n * length, 0);
  std::mt19937 rng(seed);
  std::int32_t x = 1000000, y = -500000, z = 20000;
  double t = 3.0e8;
  std::uint16_t rgb[3] = {30000, 31000, 29000};
  int ret = 1, returns = 1;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint8_t* r = out.data() + i * length;
    const bool wild = rng() % 97 == 0;
    x += wild ? static_cast<std::int32_t>(rng()) : static_cast<std::int32_t>(rng() % 61) - 20;
    y += static_cast<std::int32_t>(rng() % 9) - 4;
    z = wild ? static_cast<std::int32_t>(rng()) : z + static_cast<std::int32_t>(rng() % 201) - 100;
    if (ret >= returns) {
      returns = 1 + static_cast<int>(rng() % 4);
      ret = 1;
    } else {
      ++ret;
    }
    std::memcpy(r, &x, 4);
    std::memcpy(r + 4, &y, 4);
    std::memcpy(r + 8, &z, 4);
    const std::uint16_t intensity = static_cast<std::uint16_t>(rng() % 3 ? 100 + rng() % 50 : rng());
    std::memcpy(r + 12, &intensity, 2);
    r[14] = static_cast<std::uint8_t>(ret | (returns << 3) | ((i / 500 % 2) << 6) | (rng() % 50 == 0) << 7);
    r[15] = static_cast<std::uint8_t>(rng() % 5 ? 2 : rng());
    r[16] = static_cast<std::uint8_t>(static_cast<std::int8_t>(static_cast<int>(i % 60) - 30));
    r[17] = static_cast<std::uint8_t>(rng() % 20 ? 0 : rng());
    const std::uint16_t source = static_cast<std::uint16_t>(7 + i / 3000);
    std::memcpy(r + 18, &source, 2);
    std::size_t at = 20;
    if (format == 1 || format == 3) {
      const int kind = static_cast<int>(rng() % 50);
      if (kind == 0)
        t += 1e6 * (rng() % 3);  // another flight line
      else if (kind == 1)
        t -= 1e6;
      else if (ret == 1 && kind > 5)
        t += 1e-5 * (1 + rng() % 3);  // the next pulse; returns of a pulse share its time
      std::memcpy(r + at, &t, 8);
      at += 8;
    }
    if (format == 2 || format == 3) {
      for (std::uint16_t& c : rgb)
        c = static_cast<std::uint16_t>(rng() % 40 == 0 ? rng() : c + rng() % 7 - 3);
      if (rng() % 4 == 0)
        rgb[1] = rgb[2] = rgb[0];  // grey
      std::memcpy(r + at, rgb, 6);
      at += 6;
    }
    for (std::size_t k = 0; k < extra; ++k)
      r[at + k] = static_cast<std::uint8_t>(k % 3 == 0 ? i % 256 : (rng() % 8 ? k : rng()));
  }
  return out;
}

LaszipVlr
vlrFor(int format, std::size_t extra, int version)
{
  LaszipVlr vlr = defaultLaszipVlr(format, extra, 50000);
  for (Item& item : vlr.items)
    item.version = static_cast<std::uint16_t>(version);
  return vlr;
}

/// Encodes `records` in chunks of `chunk` points and decodes them back; every chunk must decode
/// to its records and report the bytes it was written in.
void
expectChunksRoundTrip(const LaszipVlr& vlr, const std::vector<std::uint8_t>& records, std::size_t chunk)
{
  const std::size_t length = vlr.recordLength(), n = records.size() / length;
  std::string error;
  auto enc = makeChunkEncoder(vlr, error);
  auto dec = makeChunkDecoder(vlr, error);
  ASSERT_TRUE(enc && dec) << error;
  std::vector<std::uint8_t> stream, back(records.size(), 0xAB);
  std::vector<std::size_t> sizes;
  for (std::size_t first = 0; first < n; first += chunk) {
    const std::size_t before = stream.size();
    enc->encode(records.data() + first * length, std::min(chunk, n - first), stream);
    sizes.push_back(stream.size() - before);
  }
  std::size_t pos = 0, c = 0;
  for (std::size_t first = 0; first < n; first += chunk, ++c) {
    const std::size_t count = std::min(chunk, n - first);
    const std::uint8_t* begin = stream.data() + pos;
    const std::size_t used = dec->decode(begin, begin + sizes[c], count, back.data() + first * length, error);
    ASSERT_EQ(used, sizes[c]) << "chunk " << c << ": " << error;
    pos += used;
  }
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < n; ++i)
    wrong += std::memcmp(records.data() + i * length, back.data() + i * length, length) != 0;
  EXPECT_EQ(wrong, 0u);
}

}  // namespace

// Formats 0–3, with and without extra bytes, item versions 1 and 2, several chunk sizes.
TEST(LazRoundTrip, ChunkCodersGiveBackEveryRecord)
{
  for (int format = 0; format <= 3; ++format)
    for (std::size_t extra : {std::size_t(0), std::size_t(5)})
      for (int version : {1, 2}) {
        SCOPED_TRACE("format " + std::to_string(format) + " extra " + std::to_string(extra) + " version " +
                     std::to_string(version));
        const auto records = plausibleRecords(format, extra, 7000, 11u * format + extra + version);
        for (std::size_t chunk : {std::size_t(50000), std::size_t(3000), std::size_t(999)})
          expectChunksRoundTrip(vlrFor(format, extra, version), records, chunk);
        // Chunks of 1 and 2 points on fewer records (every chunk restarts every model).
        const std::vector<std::uint8_t> few(records.begin(), records.begin() + records.size() / 20);
        for (std::size_t chunk : {std::size_t(1), std::size_t(2)})
          expectChunksRoundTrip(vlrFor(format, extra, version), few, chunk);
      }
}

// Records that change nothing, and records that change everything, at every step.
TEST(LazRoundTrip, ConstantAndRandomRecords)
{
  const LaszipVlr vlr = vlrFor(3, 3, 2);
  const std::size_t length = vlr.recordLength();
  std::vector<std::uint8_t> constant(2000 * length, 0x5A), random(2000 * length);
  std::mt19937 rng(5);
  for (auto& b : random)
    b = static_cast<std::uint8_t>(rng());
  for (int version : {1, 2}) {
    expectChunksRoundTrip(vlrFor(3, 3, version), constant, 700);
    expectChunksRoundTrip(vlrFor(3, 3, version), random, 700);
  }
}

// GPS times that hop between up to five interleaved sequences (version 2 tracks four), with
// differences beyond 32 bits, repeats and exact multiples of the last difference.
TEST(LazRoundTrip, InterleavedTimeSequences)
{
  const LaszipVlr vlr = vlrFor(1, 0, 2);
  const std::size_t n = 20000, length = 28;
  std::vector<std::uint8_t> records = plausibleRecords(1, 0, n, 3);
  std::mt19937 rng(9);
  double seq[5] = {1.0e5, 3.0e8, 7.5e8, 1.0e9, 4.0e3};
  for (std::size_t i = 0; i < n; ++i) {
    const int s = static_cast<int>(rng() % 5 == 0 ? rng() % 5 : i / 400 % 5);
    const int step = static_cast<int>(rng() % 10);
    seq[s] += step == 0 ? 0.0 : (step == 1 ? 3 * 1e-5 : (step == 2 ? -2e-5 : 1e-5));
    std::memcpy(records.data() + i * length + 20, &seq[s], 8);
  }
  for (int version : {1, 2})
    for (std::size_t chunk : {std::size_t(20000), std::size_t(5000), std::size_t(777)})
      expectChunksRoundTrip(vlrFor(1, 0, version), records, chunk);
}

// The whole file: compressLas() then decompressLaz() gives back the LAS file byte for byte
// (header, VLRs and records), for each format and chunk size, a partial last chunk included.
TEST(LazRoundTrip, CompressThenDecompressGivesTheLasFileBack)
{
  for (int format = 0; format <= 3; ++format) {
    SCOPED_TRACE("format " + std::to_string(format));
    pcl::PointCloud<PointLiDAR> cloud;
    std::vector<Eigen::Vector3d> truth;
    pcl_ls3d_test::makeUtmCloud(2345, format, {500100.0, 5000100.0, 50.0}, {500000.0, 5000000.0, 0.0}, cloud,
                                truth);
    io::SaveOptions so;
    so.las_point_format = static_cast<std::uint8_t>(format);
    so.las_vlrs.push_back({"someone", 7, "a VLR to keep", {1, 2, 3, 4}});
    std::vector<std::uint8_t> las, laz, back;
    std::string error;
    ASSERT_TRUE(io::writeLas(cloud, {500000.0, 5000000.0, 0.0}, las, error, so)) << error;
    for (std::uint32_t chunk : {50000u, 1000u, 7u}) {
      ASSERT_TRUE(io::compressLas(las.data(), las.size(), laz, error, chunk)) << error;
      if (chunk > 7) {
        EXPECT_LT(laz.size(), las.size());
      }
      io::LasHeaderInfo h;
      ASSERT_TRUE(io::readLasHeader(laz.data(), laz.size(), h, error)) << error;
      EXPECT_EQ(h.laz.compressor, 2);
      EXPECT_EQ(h.laz.chunk_size, chunk);
      EXPECT_EQ(h.laz.chunk_count, (2345 + chunk - 1) / chunk);
      EXPECT_TRUE(h.laz.chunk_table);
      EXPECT_EQ(laz[104], 0x80 | format);
      ASSERT_TRUE(io::decompressLaz(laz.data(), laz.size(), back, error)) << error;
      EXPECT_TRUE(back == las) << "chunk size " << chunk;
    }
  }
}

// A cloud saved as .laz loads as exactly the cloud saved as .las (same origin, same fields).
TEST(LazRoundTrip, SaveCloudWritesLazThatLoadsAsTheLasDoes)
{
  pcl_ls3d_test::TempDir dir("ls3d_laz_roundtrip");
  pcl::PointCloud<PointLiDAR> cloud, a, b;
  std::vector<Eigen::Vector3d> truth;
  pcl_ls3d_test::makeUtmCloud(3000, 3, {500100.0, 5000100.0, 50.0}, {500000.0, 5000000.0, 0.0}, cloud, truth);
  std::string error;
  io::SaveOptions so;
  ASSERT_TRUE(io::saveCloud(dir.file("c.laz"), cloud, {500000.0, 5000000.0, 0.0}, error, so)) << error;
  ASSERT_TRUE(io::saveCloud(dir.file("c.las"), cloud, {500000.0, 5000000.0, 0.0}, error, so)) << error;
  EXPECT_FALSE(io::saveCloud(dir.file("c.laz"), cloud, {500000.0, 5000000.0, 0.0}, error, so))
      << "never overwrites";
  io::CloudInfo ia, ib;
  ASSERT_TRUE(io::loadCloud(dir.file("c.laz"), a, ia, error)) << error;
  ASSERT_TRUE(io::loadCloud(dir.file("c.las"), b, ib, error)) << error;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    ASSERT_TRUE(a[i].x == b[i].x && a[i].y == b[i].y && a[i].z == b[i].z && a[i].gps_time == b[i].gps_time &&
                a[i].intensity == b[i].intensity && a[i].classification == b[i].classification)
        << "point " << i;
  EXPECT_EQ(ia.origin, ib.origin);
  EXPECT_TRUE(ia.las.laz.compressed);
}

// Waveform formats are refused with one line; an empty cloud makes a LAZ file of 0 points.
TEST(LazRoundTrip, RefusalsAndEmptyFiles)
{
  pcl::PointCloud<PointLiDAR> cloud;
  std::vector<Eigen::Vector3d> truth;
  pcl_ls3d_test::makeUtmCloud(10, 4, {0, 0, 0}, {0, 0, 0}, cloud, truth);
  io::SaveOptions so;
  so.las_point_format = 4;
  so.las_minor_version = 3;
  std::vector<std::uint8_t> out;
  std::string error;
  EXPECT_FALSE(io::writeLaz(cloud, Eigen::Vector3d::Zero(), out, error, so));
  EXPECT_NE(error.find("waveform"), std::string::npos) << error;
  so.las_point_format = 1;
  so.las_minor_version = 2;
  ASSERT_TRUE(io::writeLaz(pcl::PointCloud<PointLiDAR>(), Eigen::Vector3d::Zero(), out, error, so)) << error;
  pcl::PointCloud<PointLiDAR> back;
  io::CloudInfo info;
  io::LoadOptions lo;
  lo.allow_empty = true;
  ASSERT_TRUE(io::readLas(out.data(), out.size(), back, info, error, lo)) << error;
  EXPECT_EQ(back.size(), 0u);
  EXPECT_EQ(info.las.laz.chunk_count, 0u);
}

// Formats 6–8 go through the layered coders (branch laz-layered): until they are merged the
// writer refuses with their one line; once merged, the file must read back as written.
TEST(LazRoundTrip, LayeredFormatsRoundTripOrRefuseCleanly)
{
  for (int format : {6, 7, 8}) {
    SCOPED_TRACE("format " + std::to_string(format));
    pcl::PointCloud<PointLiDAR> cloud;
    std::vector<Eigen::Vector3d> truth;
    pcl_ls3d_test::makeUtmCloud(3000, format, {500100.0, 5000100.0, 50.0}, {500000.0, 5000000.0, 0.0}, cloud,
                                truth);
    io::SaveOptions so;
    so.las_point_format = static_cast<std::uint8_t>(format);
    so.las_minor_version = 4;
    std::vector<std::uint8_t> las, laz, back;
    std::string error;
    ASSERT_TRUE(io::writeLas(cloud, {500000.0, 5000000.0, 0.0}, las, error, so)) << error;
    if (!io::compressLas(las.data(), las.size(), laz, error)) {
      EXPECT_NE(error.find("not implemented"), std::string::npos) << error;
      EXPECT_EQ(error.find('\n'), std::string::npos) << error;
      continue;
    }
    io::LasHeaderInfo h;
    ASSERT_TRUE(io::readLasHeader(laz.data(), laz.size(), h, error)) << error;
    EXPECT_EQ(h.laz.compressor, 3);
    ASSERT_TRUE(io::decompressLaz(laz.data(), laz.size(), back, error)) << error;
    EXPECT_TRUE(back == las);
  }
}
