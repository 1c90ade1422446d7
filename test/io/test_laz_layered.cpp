/// \file test_laz_layered.cpp
/// \brief LAZ layered chunks (point formats 6–8, POINT14 / RGB14 / RGBNIR14 / BYTE14): real
///        files decode to exactly the point records an independent LASzip decoder produced;
///        re-encoding them gives the original chunk bytes; generated records of every layered
///        format round-trip, with empty layers for fields that never change; corrupt chunks are
///        refused with one line or decode to bounded garbage, never outside their bytes.

#include "io/laz/arithmetic_decoder.h"
#include "io/laz/laszip_items.h"
#include "io/laz_chunk_walker.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <random>
#include <tuple>

namespace laz = pcl_ls3d::io::laz;

namespace {

const std::string kData = PCL_LS3D_SHARED_DATA_DIR;

bool
haveData(const std::string& rel)
{
  return std::filesystem::exists(kData + "/" + rel);
}

// ---- record helpers ------------------------------------------------------------------------

template <typename T>
T
field(const std::uint8_t* record, std::size_t at)
{
  T v;
  std::memcpy(&v, record + at, sizeof(T));
  return v;
}

template <typename T>
void
setField(std::uint8_t* record, std::size_t at, T v)
{
  std::memcpy(record + at, &v, sizeof(T));
}

std::size_t
baseRecordLength(int format)
{
  return format == 6 ? 30 : format == 7 ? 36 : 38;
}

/// Encodes `records` in chunks of `chunk_size` (the last one partial) and returns the chunk
/// bytes, with each chunk's size in `sizes`.
std::vector<std::uint8_t>
encodeChunks(const laz::LaszipVlr& vlr, const std::vector<std::uint8_t>& records, std::size_t chunk_size,
             std::vector<std::size_t>* sizes = nullptr)
{
  std::string error;
  auto encoder = laz::makeChunkEncoder(vlr, error);
  EXPECT_TRUE(encoder) << error;
  std::vector<std::uint8_t> out;
  const std::size_t rl = vlr.recordLength(), n = records.size() / rl;
  for (std::size_t done = 0; encoder && done < n; done += chunk_size) {
    const std::size_t before = out.size();
    encoder->encode(records.data() + done * rl, std::min(chunk_size, n - done), out);
    if (sizes)
      sizes->push_back(out.size() - before);
  }
  return out;
}

/// Decodes chunks written by encodeChunks; false (with the error) when a chunk is refused.
bool
decodeChunks(const laz::LaszipVlr& vlr, const std::vector<std::uint8_t>& bytes, std::size_t n,
             std::size_t chunk_size, std::vector<std::uint8_t>& records, std::string& error)
{
  auto decoder = laz::makeChunkDecoder(vlr, error);
  if (!decoder)
    return false;
  const std::size_t rl = vlr.recordLength();
  records.assign(n * rl, 0);
  const std::uint8_t* p = bytes.data();
  const std::uint8_t* end = bytes.data() + bytes.size();
  for (std::size_t done = 0; done < n; done += chunk_size) {
    const std::size_t used =
        decoder->decode(p, end, std::min(chunk_size, n - done), records.data() + done * rl, error);
    if (used == 0)
      return false;
    p += used;
  }
  return p == end;
}

/// The layer-size table of the chunk at `chunk` (its first record is `record_length` bytes).
std::vector<std::uint32_t>
layerSizes(const std::uint8_t* chunk, std::size_t record_length, std::size_t layers)
{
  std::vector<std::uint32_t> sizes(layers);
  for (std::size_t i = 0; i < layers; ++i)
    sizes[i] = field<std::uint32_t>(chunk, record_length + 4 + 4 * i);
  return sizes;
}

std::size_t
layerCount(const laz::LaszipVlr& vlr)
{
  std::size_t n = 0;
  for (const laz::Item& item : vlr.items)
    n += item.type == laz::ItemType::Point14    ? 9
         : item.type == laz::ItemType::RgbNir14 ? 2
         : item.type == laz::ItemType::Rgb14    ? 1
                                                : item.size;
  return n;
}

// ---- generated records ---------------------------------------------------------------------

/// \brief What the generator varies (everything else is plausible airborne LiDAR).
struct Scene
{
  int format = 6;
  std::size_t extra = 0;
  unsigned channels = 1;             ///< scanner channels in use (interleaved in runs)
  bool constant_attributes = false;  ///< user data, point source, scan angle, flags, class fixed
};

/// Pulses of 1–5 returns along scan lines, GPS time rising per pulse, channels interleaved in
/// runs, colour changing slowly, extra bytes half constant and half varying.
std::vector<std::uint8_t>
generateRecords(const Scene& s, std::size_t n, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  const std::size_t base = baseRecordLength(s.format), rl = base + s.extra;
  std::vector<std::uint8_t> out(n * rl, 0);
  double t = 300000.0 + static_cast<double>(seed % 1000);
  std::int32_t x = 77055000, y = 627755000, z = 2500;
  std::uint16_t rgb[4] = {12000, 14000, 9000, 30000};
  unsigned channel = 0, returns = 1, ret = 1;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint8_t* r = out.data() + i * rl;
    if (ret > returns) {  // a new pulse
      returns = 1 + static_cast<unsigned>(rng() % 5 == 0 ? rng() % 5 : 0);
      ret = 1;
      t += 1e-5 * (1 + rng() % 3);
      if (s.channels > 1 && rng() % 40 == 0)
        channel = static_cast<unsigned>(rng() % s.channels);
      x += 20 + static_cast<std::int32_t>(rng() % 30);
      if (rng() % 500 == 0)
        y += 150, x -= 20000;
    }
    z += static_cast<std::int32_t>(rng() % 41) - 20;
    setField<std::int32_t>(r, 0, x + static_cast<std::int32_t>(ret));
    setField<std::int32_t>(r, 4, y + static_cast<std::int32_t>(rng() % 7));
    setField<std::int32_t>(r, 8, z - 300 * static_cast<std::int32_t>(ret - 1));
    setField<std::uint16_t>(r, 12, static_cast<std::uint16_t>(rng() % 4000));
    r[14] = static_cast<std::uint8_t>(ret | (returns << 4));
    const unsigned flags = s.constant_attributes ? 0u : (rng() % 100 == 0 ? 0x40u : 0u);
    r[15] = static_cast<std::uint8_t>(flags | (channel << 4));
    r[16] = static_cast<std::uint8_t>(s.constant_attributes ? 2 : (rng() % 10 < 7 ? 2 : 6));
    r[17] = static_cast<std::uint8_t>(s.constant_attributes ? 0 : rng() % 3);
    setField<std::int16_t>(r, 18,
                           static_cast<std::int16_t>(s.constant_attributes ? 0 : (x / 7) % 3000 - 1500));
    setField<std::uint16_t>(r, 20, static_cast<std::uint16_t>(s.constant_attributes ? 706 : 706 + channel));
    setField<double>(r, 22, t);
    if (s.format >= 7) {
      if (rng() % 8 == 0)
        for (auto& c : rgb)
          c = static_cast<std::uint16_t>(c + static_cast<int>(rng() % 513) - 256);
      const std::uint16_t grey = rng() % 10 == 0 ? rgb[0] : 0;
      for (int c = 0; c < 3; ++c)
        setField<std::uint16_t>(r, 30 + 2 * c, grey ? grey : rgb[c]);
      if (s.format == 8)
        setField<std::uint16_t>(r, 36, rgb[3]);
    }
    for (std::size_t b = 0; b < s.extra; ++b)
      r[base + b] = static_cast<std::uint8_t>(b % 2 == 0 ? 0xA5 : rng() % 7 + b);
    ++ret;
  }
  return out;
}

// ---- real files ----------------------------------------------------------------------------

struct Twin
{
  const char* laz;
  const char* las;
  int format;
};

// The LAZ files of MANIFEST section E with a LAS twin decoded by laz-perf 0.0.7.
const std::vector<Twin>&
twins()
{
  static const std::vector<Twin> list = {
      {"laz/ign/test_data_77050_627755_LA93_IGN69.laz",
       "registration/ign_lidarhd/test_data_77050_627755_LA93_IGN69.las", 8},
      {"laz/ign/test_data_77050_627760_LA93_IGN69.laz",
       "registration/ign_lidarhd/test_data_77050_627760_LA93_IGN69.las", 8},
      {"laz/ign/test_data_77055_627755_LA93_IGN69.laz",
       "registration/ign_lidarhd/test_data_77055_627755_LA93_IGN69.las", 8},
      {"laz/ign/test_data_77055_627760_LA93_IGN69.laz",
       "registration/ign_lidarhd/test_data_77055_627760_LA93_IGN69.las", 8},
      {"laz/ign/test_data_77060_627760_LA93_IGN69.laz",
       "registration/ign_lidarhd/test_data_77060_627760_LA93_IGN69.las", 8},
      {"laz/ign/test_semis_2023_0292_6833_LA93_IGN69.laz",
       "registration/ign_lidarhd/test_semis_2023_0292_6833_LA93_IGN69.las", 6},
      {"laz/ign/test_semis_2021_0382_6565_LA93_IGN69_cropped.laz",
       "registration/ign_lidarhd/test_semis_2021_0382_6565_LA93_IGN69_cropped.las", 7},
      {"laz/ign/Semis_2022_0906_6665_LA93_IGN69_ok.laz",
       "registration/ign_lidarhd/Semis_2022_0906_6665_LA93_IGN69_ok.las", 7},
      {"laz/ign/sample_lareunion_epsg2975.laz", "registration/ign_lidarhd/sample_lareunion_epsg2975.las", 8},
      {"laz/ign/las_with_origin_dsmMarker.laz", "registration/ign_lidarhd/las_with_origin_dsmMarker.las", 8},
      {"laz/ign/target_cloud_crop.laz", "registration/ign_lidarhd/target_cloud_crop.las", 7},
      {"laz/laspy/1_4_w_evlr.laz", "laz/laspy/1_4_w_evlr.las", 6},
  };
  return list;
}

laz_test::WalkResult
walk(const std::string& rel, laz_test::LasFile& file)
{
  EXPECT_TRUE(laz_test::openLasFile(kData + "/" + rel, file)) << rel;
  return laz_test::walkLaz(file);
}

}  // namespace

// Every twin pair: the decoded records equal the LAS twin's, byte for byte (PF6, PF7, PF8, PF8
// with 19 extra bytes, and a file with EVLRs after its points).
TEST(LazLayeredReal, TwinsDecodeToTheirLasRecordsByteForByte)
{
  if (!haveData("laz/ign"))
    GTEST_SKIP() << "shared data folder " << kData << " is absent; real-data test skipped";
  std::map<int, int> formats;
  bool extra_bytes = false;
  for (const Twin& t : twins()) {
    laz_test::LasFile laz_file, las_file;
    const laz_test::WalkResult r = walk(t.laz, laz_file);
    ASSERT_TRUE(r.ok) << t.laz << ": " << r.error;
    ASSERT_TRUE(laz_test::openLasFile(kData + "/" + t.las, las_file)) << t.las;
    EXPECT_EQ(laz_file.point_format, t.format) << t.laz;
    EXPECT_EQ(r.vlr.compressor, laz::Compressor::LayeredChunked) << t.laz;
    EXPECT_EQ(las_file.record_length, laz_file.record_length) << t.las;
    const std::vector<std::uint8_t> want = las_file.rawRecords();
    ASSERT_EQ(want.size(), r.records.size()) << t.laz;
    EXPECT_TRUE(want == r.records) << t.laz << " decodes to other records than " << t.las;
    ++formats[laz_file.point_format];
    extra_bytes |= laz_file.record_length > baseRecordLength(laz_file.point_format);
  }
  EXPECT_EQ(formats.size(), 3u) << "point formats 6, 7 and 8 are all covered";
  EXPECT_TRUE(extra_bytes) << "a twin with extra bytes (BYTE14) is covered";
}

// The extra-dimensions file holds the points of test_data_77055_627755 (same scale, another
// order) plus two doubles declared by its Extra Bytes VLR, dtm_marker and dsm_marker: the base
// records are the twin's as a multiset, and every marker is exactly 0.0 or 1.0, both present.
TEST(LazLayeredReal, ExtraDimensionsKeepTheirBytes)
{
  const std::string rel = "laz/ign/test_data_77055_627755_LA93_IGN69_extra_dims.laz";
  const std::string twin = "registration/ign_lidarhd/test_data_77055_627755_LA93_IGN69.las";
  if (!haveData(rel) || !haveData(twin))
    GTEST_SKIP() << "shared data folder " << kData << " is absent; real-data test skipped";
  laz_test::LasFile file, twin_file;
  const laz_test::WalkResult r = walk(rel, file);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_TRUE(laz_test::openLasFile(kData + "/" + twin, twin_file));
  ASSERT_EQ(file.point_count, twin_file.point_count);
  ASSERT_EQ(r.vlr.items.back().type, laz::ItemType::Byte14);
  ASSERT_EQ(r.vlr.items.back().size, 16u);
  ASSERT_EQ(file.record_length, 54u);
  const laz_test::VlrRef* eb = file.findVlr("LASF_Spec", 4);
  ASSERT_NE(eb, nullptr) << "an Extra Bytes VLR";
  ASSERT_EQ(eb->size, 2u * 192u);
  EXPECT_EQ(file.bytes[eb->data + 2], 10) << "double";
  EXPECT_EQ(file.bytes[eb->data + 192 + 2], 10) << "double";
  const std::vector<std::uint8_t> twin_records = twin_file.rawRecords();
  std::vector<std::vector<std::uint8_t>> ours, theirs;
  std::map<double, std::size_t> markers;
  for (std::size_t i = 0; i < file.point_count; ++i) {
    const std::uint8_t* a = r.records.data() + i * 54;
    ours.emplace_back(a, a + 38);
    theirs.emplace_back(twin_records.begin() + i * 38, twin_records.begin() + (i + 1) * 38);
    ++markers[field<double>(a, 38)];
    ++markers[field<double>(a, 46)];
  }
  std::sort(ours.begin(), ours.end());
  std::sort(theirs.begin(), theirs.end());
  EXPECT_TRUE(ours == theirs);
  ASSERT_EQ(markers.size(), 2u);
  EXPECT_EQ(markers.begin()->first, 0.0);
  EXPECT_EQ(markers.rbegin()->first, 1.0);
}

// 697,721 points with several extra-byte blocks and no twin: every point decodes, inside the
// header's bounds, with valid return numbers, and the extra bytes match the VLR's sizes.
TEST(LazLayeredReal, SeveralExtraByteBlocksDecodePlausibly)
{
  const std::string rel = "laz/ign/las_with_several_extra_byte_bloc.laz";
  if (!haveData(rel))
    GTEST_SKIP() << "shared data folder " << kData << " is absent; real-data test skipped";
  laz_test::LasFile file;
  const laz_test::WalkResult r = walk(rel, file);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(file.point_count, 697721u);
  EXPECT_EQ(r.vlr.items.back().type, laz::ItemType::Byte14);
  // Two Extra Bytes VLRs ("several blocks"); each 192-byte descriptor: data type at 2 (1–10 scalars, 11–30 the deprecated 2- and
  // 3-element arrays), options at 3 (the byte count for type 0, "undocumented bytes").
  static const std::size_t kTypeBytes[] = {0, 1, 1, 2, 2, 4, 4, 8, 8, 4, 8};
  std::size_t declared = 0, blocks = 0;
  for (const laz_test::VlrRef& eb : file.vlrs) {
    if (eb.user != "LASF_Spec" || eb.record_id != 4)
      continue;
    ++blocks;
    for (std::size_t d = 0; d + 192 <= eb.size; d += 192) {
      const std::uint8_t type = file.bytes[eb.data + d + 2];
      declared += type == 0    ? file.bytes[eb.data + d + 3]
                  : type <= 10 ? kTypeBytes[type]
                  : type <= 20 ? 2 * kTypeBytes[type - 10]
                  : type <= 30 ? 3 * kTypeBytes[type - 20]
                               : 0;
    }
  }
  EXPECT_EQ(blocks, 2u);
  EXPECT_EQ(declared, r.vlr.items.back().size);
  const auto scale = [&](int k) { return laz_test::get<double>(file.bytes, 131 + 8 * k); };
  const auto offset = [&](int k) { return laz_test::get<double>(file.bytes, 155 + 8 * k); };
  const auto bound = [&](int k, bool max) {
    return laz_test::get<double>(file.bytes, 179 + 16 * k + (max ? 0 : 8));
  };
  std::size_t outside = 0, bad_returns = 0;
  for (std::size_t i = 0; i < file.point_count; ++i) {
    const std::uint8_t* p = r.records.data() + i * file.record_length;
    for (int k = 0; k < 3; ++k) {
      const double v = field<std::int32_t>(p, 4 * k) * scale(k) + offset(k);
      outside += v < bound(k, false) - 1e-6 || v > bound(k, true) + 1e-6;
    }
    const int ret = p[14] & 15, returns = p[14] >> 4;
    bad_returns += ret < 1 || ret > returns;
  }
  EXPECT_EQ(outside, 0u);
  EXPECT_EQ(bad_returns, 0u);
}

// COPC nodes are layered chunks of varying size. simple.copc.laz holds simple.las's 1,065
// points (PF3 there, PF7 here, another offset, another order): the same multiset of
// coordinates, intensity, colour and GPS time.
TEST(LazLayeredReal, CopcNodesDecodeToTheSourcePoints)
{
  const std::string rel = "laz/laspy/simple.copc.laz", src = "laz/laspy/simple.las";
  if (!haveData(rel) || !haveData(src))
    GTEST_SKIP() << "shared data folder " << kData << " is absent; real-data test skipped";
  laz_test::LasFile copc, las;
  const laz_test::WalkResult r = walk(rel, copc);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_GT(r.chunks, 1u);
  ASSERT_TRUE(laz_test::openLasFile(kData + "/" + src, las));
  ASSERT_EQ(las.point_format, 3);
  ASSERT_EQ(copc.point_count, las.point_count);
  using Key = std::tuple<std::int64_t, std::int64_t, std::int64_t, int, int, int, int, double>;
  const auto offset = [](const laz_test::LasFile& f, int k) {
    return laz_test::get<double>(f.bytes, 155 + 8 * k);
  };
  std::int64_t shift[3];
  for (int k = 0; k < 3; ++k)
    shift[k] = std::llround((offset(copc, k) - offset(las, k)) / 0.01);
  std::vector<Key> a, b;
  for (std::size_t i = 0; i < copc.point_count; ++i) {
    const std::uint8_t* p = r.records.data() + i * copc.record_length;
    a.emplace_back(field<std::int32_t>(p, 0) + shift[0], field<std::int32_t>(p, 4) + shift[1],
                   field<std::int32_t>(p, 8) + shift[2], field<std::uint16_t>(p, 12),
                   field<std::uint16_t>(p, 30), field<std::uint16_t>(p, 32), field<std::uint16_t>(p, 34),
                   field<double>(p, 22));
    const std::uint8_t* q = las.bytes.data() + las.offset_to_points + i * las.record_length;
    b.emplace_back(field<std::int32_t>(q, 0), field<std::int32_t>(q, 4), field<std::int32_t>(q, 8),
                   field<std::uint16_t>(q, 12), field<std::uint16_t>(q, 28), field<std::uint16_t>(q, 30),
                   field<std::uint16_t>(q, 32), field<double>(q, 20));
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_TRUE(a == b);
}

// Re-encoding the decoded records of every twin reproduces the original chunks byte for byte
// (the coder makes LASzip's choices), so the point data is the same size, well within 1 %.
TEST(LazLayeredReal, ReencodingGivesTheOriginalChunkBytes)
{
  if (!haveData("laz/ign"))
    GTEST_SKIP() << "shared data folder " << kData << " is absent; real-data test skipped";
  for (const Twin& t : twins()) {
    laz_test::LasFile file;
    const laz_test::WalkResult r = walk(t.laz, file);
    ASSERT_TRUE(r.ok) << t.laz << ": " << r.error;
    std::vector<std::size_t> sizes;
    const std::vector<std::uint8_t> bytes = encodeChunks(r.vlr, r.records, r.vlr.chunk_size, &sizes);
    EXPECT_LE(std::fabs(double(bytes.size()) - double(r.point_data_bytes)), 0.01 * double(r.point_data_bytes))
        << t.laz;
    EXPECT_EQ(sizes, r.chunk_bytes) << t.laz;
    const std::uint8_t* original = file.bytes.data() + file.offset_to_points + 8;
    EXPECT_TRUE(std::equal(bytes.begin(), bytes.end(), original)) << t.laz;
  }
}

// LASzip-written files with four scanner channels (test/data/laz_layered, versions 3 and 4):
// version 3 hands the channel to RGB / NIR / BYTE only on a switch and predicts from the previous
// channel's value after switching back; both decode to LASzip's own uncompressed records and
// re-encode to LASzip's chunk bytes.
TEST(LazLayeredLaszip, MultiChannelFilesMatchLaszip)
{
  const std::string dir = std::string(PCL_LS3D_TEST_SOURCE_DIR) + "/data/laz_layered/";
  for (const std::string name : {"laszip_v3_pf8_4channels", "laszip_v4_pf8_4channels"}) {
    laz_test::LasFile laz_file, las_file;
    ASSERT_TRUE(laz_test::openLasFile(dir + name + ".laz", laz_file)) << name;
    ASSERT_TRUE(laz_test::openLasFile(dir + name + ".las", las_file)) << name;
    const laz_test::WalkResult r = laz_test::walkLaz(laz_file);
    ASSERT_TRUE(r.ok) << name << ": " << r.error;
    EXPECT_EQ(r.vlr.items.size(), 3u);
    EXPECT_EQ(r.vlr.items[0].version, name.find("_v3_") != std::string::npos ? 3 : 4);
    EXPECT_EQ(r.chunks, 3u);
    EXPECT_TRUE(r.records == las_file.rawRecords()) << name;
    std::vector<std::size_t> sizes;
    const std::vector<std::uint8_t> bytes = encodeChunks(r.vlr, r.records, r.vlr.chunk_size, &sizes);
    EXPECT_EQ(sizes, r.chunk_bytes) << name;
    EXPECT_TRUE(std::equal(bytes.begin(), bytes.end(), laz_file.bytes.data() + laz_file.offset_to_points + 8))
        << name;
  }
}

// ---- round trips on generated records --------------------------------------------------------

struct RoundTripCase
{
  Scene scene;
  std::size_t points, chunk_size;
  std::uint16_t version;
};

class LazLayeredRoundTrip : public ::testing::TestWithParam<RoundTripCase>
{};

TEST_P(LazLayeredRoundTrip, EncodeDecodeIsIdentity)
{
  const RoundTripCase& c = GetParam();
  laz::LaszipVlr vlr =
      laz::defaultLaszipVlr(c.scene.format, c.scene.extra, static_cast<std::uint32_t>(c.chunk_size));
  for (laz::Item& item : vlr.items)
    item.version = c.version;
  const std::vector<std::uint8_t> records = generateRecords(c.scene, c.points, 17 + c.points);
  std::vector<std::size_t> sizes;
  const std::vector<std::uint8_t> bytes = encodeChunks(vlr, records, c.chunk_size, &sizes);
  EXPECT_EQ(sizes.size(), (c.points + c.chunk_size - 1) / c.chunk_size);
  std::vector<std::uint8_t> back;
  std::string error;
  ASSERT_TRUE(decodeChunks(vlr, bytes, c.points, c.chunk_size, back, error)) << error;
  EXPECT_TRUE(back == records);
  if (c.chunk_size >= 50) {  // compresses: well under the raw size
    EXPECT_LT(bytes.size(), records.size() / 2);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Formats, LazLayeredRoundTrip,
    ::testing::Values(RoundTripCase{{6, 0, 1, false}, 120000, 50000, 3},  // default chunks, partial last
                      RoundTripCase{{6, 0, 4, false}, 20000, 7, 3},       // 4 channels, tiny chunks
                      RoundTripCase{{6, 0, 1, true}, 3000, 1, 3},         // one point per chunk
                      RoundTripCase{{7, 0, 2, false}, 60000, 50000, 3},
                      RoundTripCase{{7, 5, 3, false}, 9000, 1000, 4},  // version 4 items
                      RoundTripCase{{8, 0, 2, false}, 60000, 50000, 3},
                      RoundTripCase{{8, 12, 4, false}, 30000, 7000, 3},
                      RoundTripCase{{8, 3, 4, true}, 50001, 50000, 4},
                      RoundTripCase{{6, 9, 2, true}, 777, 50000, 3}));

// A field that never changes in a chunk leaves its layer empty (size 0), as LASzip writes it,
// and decodes as "unchanged"; changing fields get bytes.
TEST(LazLayeredRoundTrip2, ConstantFieldsLeaveTheirLayersEmpty)
{
  const Scene scene{8, 4, 1, true};
  laz::LaszipVlr vlr = laz::defaultLaszipVlr(8, 4, 5000);
  const std::vector<std::uint8_t> records = generateRecords(scene, 5000, 3);
  const std::vector<std::uint8_t> bytes = encodeChunks(vlr, records, 5000);
  const std::vector<std::uint32_t> sizes = layerSizes(bytes.data(), 42, layerCount(vlr));
  ASSERT_EQ(sizes.size(), 9u + 2u + 4u);
  // POINT14: XY, Z, class, flags, intensity, scan angle, user data, point source, GPS time.
  EXPECT_GT(sizes[0], 0u);
  EXPECT_GT(sizes[1], 0u);
  EXPECT_EQ(sizes[2], 0u);
  EXPECT_EQ(sizes[3], 0u);
  EXPECT_GT(sizes[4], 0u);
  EXPECT_EQ(sizes[5], 0u);
  EXPECT_EQ(sizes[6], 0u);
  EXPECT_EQ(sizes[7], 0u);
  EXPECT_GT(sizes[8], 0u);
  EXPECT_GT(sizes[9], 0u);   // RGB varies
  EXPECT_GT(sizes[10], 0u);  // NIR varies
  EXPECT_EQ(sizes[11], 0u);  // extra bytes 0 and 2 are constant, 1 and 3 vary
  EXPECT_GT(sizes[12], 0u);
  EXPECT_EQ(sizes[13], 0u);
  EXPECT_GT(sizes[14], 0u);
  std::vector<std::uint8_t> back;
  std::string error;
  ASSERT_TRUE(decodeChunks(vlr, bytes, 5000, 5000, back, error)) << error;
  EXPECT_TRUE(back == records);
}

// Versions 3 and 4 code the same records differently only after the scanner channel returns to
// a channel already in use with a colour that changed meanwhile: each version decodes its own
// chunks exactly, and reading version-4 chunks as version 3 goes wrong.
TEST(LazLayeredRoundTrip2, Version4FixesTheChannelSwitchPrediction)
{
  laz::LaszipVlr v3 = laz::defaultLaszipVlr(7, 2, 4000), v4 = v3;
  for (laz::Item& item : v4.items)
    item.version = 4;
  const std::vector<std::uint8_t> records = generateRecords({7, 2, 3, false}, 4000, 11);
  const std::vector<std::uint8_t> bytes3 = encodeChunks(v3, records, 4000);
  const std::vector<std::uint8_t> bytes4 = encodeChunks(v4, records, 4000);
  EXPECT_NE(bytes3, bytes4);
  std::vector<std::uint8_t> back;
  std::string error;
  ASSERT_TRUE(decodeChunks(v3, bytes3, 4000, 4000, back, error)) << error;
  EXPECT_TRUE(back == records);
  ASSERT_TRUE(decodeChunks(v4, bytes4, 4000, 4000, back, error)) << error;
  EXPECT_TRUE(back == records);
  const bool refused = !decodeChunks(v3, bytes4, 4000, 4000, back, error);
  EXPECT_TRUE(refused || back != records);
  // POINT14 is the same in both versions: its layers are identical.
  const std::size_t n = 9;
  const auto s3 = layerSizes(bytes3.data(), 38, n), s4 = layerSizes(bytes4.data(), 38, n);
  EXPECT_EQ(s3, s4);
}

// ---- hostile input ---------------------------------------------------------------------------

namespace {

struct HostileFixture
{
  laz::LaszipVlr vlr = laz::defaultLaszipVlr(8, 3, 1000);
  std::vector<std::uint8_t> records = generateRecords({8, 3, 2, false}, 1000, 5);
  std::vector<std::uint8_t> chunk = encodeChunks(vlr, records, 1000);
  std::unique_ptr<laz::ChunkDecoder> decoder;
  std::vector<std::uint8_t> out = std::vector<std::uint8_t>(records.size());
  std::string error;

  HostileFixture()
  {
    decoder = laz::makeChunkDecoder(vlr, error);
  }

  /// Decodes `bytes` as a chunk of 1000 points, from a copy of exactly that size (so ASan sees
  /// any read past it).
  std::size_t
  decode(const std::vector<std::uint8_t>& bytes, std::size_t count = 1000)
  {
    std::unique_ptr<std::uint8_t[]> copy(new std::uint8_t[std::max<std::size_t>(bytes.size(), 1)]);
    std::copy(bytes.begin(), bytes.end(), copy.get());
    error.clear();
    return decoder->decode(copy.get(), copy.get() + bytes.size(), count, out.data(), error);
  }
};

}  // namespace

TEST(LazLayeredHostile, EveryTruncationIsRefusedWithOneLine)
{
  HostileFixture f;
  ASSERT_TRUE(f.decoder) << f.error;
  ASSERT_EQ(f.decode(f.chunk), f.chunk.size());
  for (std::size_t len = 0; len < f.chunk.size(); ++len) {
    const std::vector<std::uint8_t> cut(f.chunk.begin(), f.chunk.begin() + len);
    ASSERT_EQ(f.decode(cut), 0u) << "truncated to " << len;
    EXPECT_FALSE(f.error.empty());
    EXPECT_EQ(f.error.find('\n'), std::string::npos);
  }
}

TEST(LazLayeredHostile, WrongCountsAndLayerSizesAreRefused)
{
  HostileFixture f;
  ASSERT_TRUE(f.decoder) << f.error;
  EXPECT_EQ(f.decode(f.chunk, 999), 0u) << "count field says 1000";
  EXPECT_NE(f.error.find("1000"), std::string::npos) << f.error;
  EXPECT_EQ(f.decode(f.chunk, 0), 0u);
  std::vector<std::uint8_t> huge = f.chunk;
  setField<std::uint32_t>(huge.data(), 41 + 4, 0xFFFFFFFFu);  // first layer size
  EXPECT_EQ(f.decode(huge), 0u);
  EXPECT_NE(f.error.find("past the end"), std::string::npos) << f.error;
  // A layer shorter than its records need: shrink the last non-empty layer and the chunk.
  const std::size_t layers = layerCount(f.vlr);
  std::vector<std::uint32_t> sizes = layerSizes(f.chunk.data(), 41, layers);
  std::size_t last = layers - 1;
  while (sizes[last] == 0)
    --last;
  std::vector<std::uint8_t> short_layer = f.chunk;
  const std::uint32_t cut = sizes[last] - 4;
  setField<std::uint32_t>(short_layer.data(), 41 + 4 + 4 * last, 4u);
  short_layer.resize(short_layer.size() - cut);
  EXPECT_EQ(f.decode(short_layer), 0u);
  EXPECT_NE(f.error.find("corrupt"), std::string::npos) << f.error;
}

// Random layer bytes (with a consistent size table) and random bit flips in a real chunk:
// decode returns the chunk's size or 0 with a reason, and never reads outside the chunk.
TEST(LazLayeredHostile, GarbageLayersDecodeBoundedOrAreRefused)
{
  HostileFixture f;
  ASSERT_TRUE(f.decoder) << f.error;
  std::mt19937_64 rng(99);
  const std::size_t head = 41 + 4 + 4 * layerCount(f.vlr);
  std::size_t refused = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<std::uint8_t> bytes = f.chunk;
    if (trial % 2 == 0) {
      for (std::size_t i = head; i < bytes.size(); ++i)
        bytes[i] = static_cast<std::uint8_t>(trial % 10 == 0 ? 0xFF : rng());
    } else {
      for (int flips = 0; flips < 1 + trial % 5; ++flips) {
        const std::size_t at = head + rng() % (bytes.size() - head);
        bytes[at] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
      }
    }
    const std::size_t used = f.decode(bytes);
    if (used == 0) {
      ++refused;
      EXPECT_FALSE(f.error.empty());
    } else {
      EXPECT_EQ(used, bytes.size());
    }
  }
  RecordProperty("refused", static_cast<int>(refused));
}

// Garbage can push the arithmetic decoder's value past its interval; the symbol decoder's table
// look-up must stay inside the table (this read past it before the index was clamped: run
// under -fsanitize=address to see it), and every symbol stays in range.
TEST(LazLayeredHostile, GarbageKeepsTheSymbolDecoderInsideItsTable)
{
  std::mt19937_64 rng(2024);
  std::size_t out_of_range = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // Value == length at the start (four 0xFF bytes) is where a valid stream can never be.
    std::vector<std::uint8_t> garbage(8 + rng() % 56, 0xFF);
    for (std::size_t i = 4; i < garbage.size() && trial % 2 == 1; ++i)
      garbage[i] = static_cast<std::uint8_t>(rng());
    laz::ArithmeticDecoder dec(garbage.data(), garbage.data() + garbage.size());
    laz::SymbolModel small(128), mid(256), big(2048);
    for (int i = 0; i < 400; ++i) {
      out_of_range += dec.decodeSymbol(small) >= 128;
      out_of_range += dec.decodeSymbol(mid) >= 256;
      out_of_range += dec.decodeSymbol(big) >= 2048;
    }
  }
  EXPECT_EQ(out_of_range, 0u);
}

// A one-point chunk is its raw record: it decodes even when a writer left every layer empty.
TEST(LazLayeredHostile, OnePointChunkNeedsNoLayerBytes)
{
  HostileFixture f;
  ASSERT_TRUE(f.decoder) << f.error;
  const std::size_t head = 41 + 4 + 4 * layerCount(f.vlr);
  std::vector<std::uint8_t> chunk(head, 0);
  std::copy(f.records.begin(), f.records.begin() + 41, chunk.begin());
  setField<std::uint32_t>(chunk.data(), 41, 1u);
  EXPECT_EQ(f.decode(chunk, 1), head) << f.error;
  EXPECT_TRUE(std::equal(f.records.begin(), f.records.begin() + 41, f.out.begin()));
}

TEST(LazLayeredHostile, ItemListsOutOfOrderOrMisSizedAreRefused)
{
  std::string error;
  laz::LaszipVlr vlr = laz::defaultLaszipVlr(8, 2, 50000);
  EXPECT_TRUE(laz::makeChunkDecoder(vlr, error)) << error;
  laz::LaszipVlr swapped = vlr;
  std::swap(swapped.items[0], swapped.items[1]);
  EXPECT_FALSE(laz::makeChunkDecoder(swapped, error));
  EXPECT_FALSE(laz::makeChunkEncoder(swapped, error));
  EXPECT_FALSE(error.empty());
  laz::LaszipVlr wrong_size = vlr;
  wrong_size.items[1].size = 6;  // RGBNIR14 is 8 bytes
  EXPECT_FALSE(laz::makeChunkDecoder(wrong_size, error));
  laz::LaszipVlr twice = vlr;
  twice.items.push_back(twice.items.back());
  EXPECT_FALSE(laz::makeChunkDecoder(twice, error));
  laz::LaszipVlr point_size = vlr;
  point_size.items[0].size = 20;
  EXPECT_FALSE(laz::makeChunkDecoder(point_size, error));
  EXPECT_EQ(error.find('\n'), std::string::npos);
}
