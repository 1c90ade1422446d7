/// \file test_las_io.cpp
/// \brief LAS writer -> reader round trips for every version/point-format pair the specification
///        allows, header fields against an independent recount, extra bytes, 1.4 point counts.

#include <pcl_ls3d/io/las_io.h>

#include "io/io_test_utils.h"

#include <gtest/gtest.h>

#include <cstring>
#include <tuple>

using namespace pcl_ls3d;
using pcl_ls3d_test::makeUtmCloud;

namespace {

const Eigen::Vector3d kBase(512345.0, 5412345.0, 321.0);  // UTM-scale easting/northing
const Eigen::Vector3d kOrigin(512000.0, 5412000.0, 0.0);

template <typename T>
T
at(const std::vector<std::uint8_t>& b, std::size_t offset)
{
  T v;
  std::memcpy(&v, b.data() + offset, sizeof(T));
  return v;
}

template <typename T>
void
set(std::vector<std::uint8_t>& b, std::size_t offset, T v)
{
  std::memcpy(b.data() + offset, &v, sizeof(T));
}

}  // namespace

class LasRoundTrip : public ::testing::TestWithParam<std::tuple<int, int>>
{};

// Every kept field must come back identical: coordinates are whole millimetres at a 1 mm quantum,
// so the only error is the float rounding of local values within +-400 m (< 3.1e-5 m); 1e-4 m
// tolerance. Integer fields and GPS time (stored as double) must match exactly.
TEST_P(LasRoundTrip, KeptFieldsAndHeaderAreExact)
{
  const int minor = std::get<0>(GetParam()), format = std::get<1>(GetParam());
  pcl::PointCloud<PointLiDAR> cloud, back;
  std::vector<Eigen::Vector3d> truth;
  makeUtmCloud(500, format, kBase, kOrigin, cloud, truth, 7 + format);

  io::SaveOptions so;
  so.las_point_format = static_cast<std::uint8_t>(format);
  so.las_minor_version = static_cast<std::uint8_t>(minor);
  std::vector<std::uint8_t> bytes;
  std::string error;
  ASSERT_TRUE(io::writeLas(cloud, kOrigin, bytes, error, so)) << error;

  io::CloudInfo info;
  io::LoadOptions lo;
  lo.use_origin = true;
  lo.origin = kOrigin;
  ASSERT_TRUE(io::readLas(bytes.data(), bytes.size(), back, info, error, lo)) << error;
  ASSERT_EQ(back.size(), cloud.size());
  const bool has_time = format == 1 || format >= 3;
  Eigen::Vector3d lo_truth = truth[0], hi_truth = truth[0];
  std::uint64_t by_return[15] = {};
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const auto &a = cloud[i], &b = back[i];
    const Eigen::Vector3d xb = b.getVector3fMap().cast<double>() + kOrigin;
    EXPECT_LT((xb - truth[i]).cwiseAbs().maxCoeff(), 1e-4) << "point " << i;
    EXPECT_EQ(a.intensity, b.intensity);
    EXPECT_EQ(a.classification, b.classification);
    EXPECT_EQ(a.point_source_id, b.point_source_id);
    EXPECT_EQ(a.return_number, b.return_number);
    EXPECT_EQ(a.number_of_returns, b.number_of_returns);
    EXPECT_EQ(has_time ? a.gps_time : 0.0, b.gps_time);
    lo_truth = lo_truth.cwiseMin(truth[i]);
    hi_truth = hi_truth.cwiseMax(truth[i]);
    ++by_return[a.return_number - 1];
  }
  // Header against the spec and an independent recount.
  const std::size_t header_size = minor == 4 ? 375 : (minor == 3 ? 235 : 227);
  EXPECT_EQ(info.las.version_minor, minor);
  EXPECT_EQ(info.las.point_format, format);
  EXPECT_EQ(info.las.header_size, header_size);
  EXPECT_EQ(info.las.offset_to_points, header_size);
  EXPECT_EQ(info.las.record_length, io::lasPointRecordLength(format));
  EXPECT_EQ(bytes.size(), header_size + cloud.size() * io::lasPointRecordLength(format));
  EXPECT_EQ(info.las.point_count, cloud.size());
  EXPECT_EQ(info.las.legacy_point_count, (minor == 4 && format >= 6) ? 0u : cloud.size());
  for (int r = 0; r < (minor == 4 ? 15 : 5); ++r)
    EXPECT_EQ(info.las.points_by_return[r], by_return[r]) << "return " << r + 1;
  EXPECT_LT((info.las.min - lo_truth).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((info.las.max - hi_truth).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_EQ((info.las.global_encoding >> 4) & 1, (minor == 4 && format >= 6) ? 1 : 0);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(bytes.data()), 4), "LASF");
}

static std::vector<std::tuple<int, int>>
validPairs()
{
  std::vector<std::tuple<int, int>> pairs;
  for (int minor = 0; minor <= 4; ++minor)
    for (int format = 0; format <= 10; ++format) {
      const int needs = format <= 1 ? 0 : (format <= 3 ? 2 : (format <= 5 ? 3 : 4));
      if (minor >= needs)
        pairs.emplace_back(minor, format);
    }
  return pairs;  // 2 + 2 + 4 + 6 + 11 = 25 pairs
}

INSTANTIATE_TEST_SUITE_P(AllVersionsAndFormats, LasRoundTrip, ::testing::ValuesIn(validPairs()),
                         [](const auto& info) {
                           return "v1" + std::to_string(std::get<0>(info.param)) + "_pf" +
                                  std::to_string(std::get<1>(info.param));
                         });

// Auto origin: UTM coordinates are centred on the rounded bbox centre and come back within 1 mm.
TEST(LasIO, UtmAutoOriginRoundTripWithinOneMillimetre)
{
  pcl::PointCloud<PointLiDAR> cloud, back;
  std::vector<Eigen::Vector3d> truth;
  makeUtmCloud(2000, 3, kBase, kOrigin, cloud, truth);
  std::vector<std::uint8_t> bytes;
  std::string error;
  ASSERT_TRUE(io::writeLas(cloud, kOrigin, bytes, error)) << error;
  io::CloudInfo info;
  ASSERT_TRUE(io::readLas(bytes.data(), bytes.size(), back, info, error)) << error;
  EXPECT_EQ(info.origin, io::chooseOrigin(info.min_file, info.max_file));
  EXPECT_GT(info.origin[1], 5e6);  // shifted
  EXPECT_EQ(info.origin[2], 0.0);  // heights < 1e4 are not shifted
  for (std::size_t i = 0; i < back.size(); ++i) {
    const Eigen::Vector3d xb = back[i].getVector3fMap().cast<double>() + info.origin;
    ASSERT_LT((xb - truth[i]).cwiseAbs().maxCoeff(), 1e-3);
  }
}

// Records longer than the format needs (extra bytes) are skipped, not misread.
TEST(LasIO, ExtraBytesPerRecordAreSkipped)
{
  pcl::PointCloud<PointLiDAR> cloud, back;
  std::vector<Eigen::Vector3d> truth;
  makeUtmCloud(50, 8, kBase, kOrigin, cloud, truth);
  io::SaveOptions so;
  so.las_point_format = 8;
  so.las_minor_version = 4;
  std::vector<std::uint8_t> bytes;
  std::string error;
  ASSERT_TRUE(io::writeLas(cloud, kOrigin, bytes, error, so)) << error;
  const std::size_t extra = 7, rl = 38, hs = 375;
  std::vector<std::uint8_t> padded(bytes.begin(), bytes.begin() + hs);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    padded.insert(padded.end(), bytes.begin() + hs + i * rl, bytes.begin() + hs + (i + 1) * rl);
    padded.insert(padded.end(), extra, 0xAB);
  }
  set<std::uint16_t>(padded, 105, static_cast<std::uint16_t>(rl + extra));
  io::CloudInfo info;
  ASSERT_TRUE(io::readLas(padded.data(), padded.size(), back, info, error)) << error;
  EXPECT_EQ(info.las.extra_bytes_per_record, extra);
  ASSERT_EQ(back.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_EQ(back[i].classification, cloud[i].classification);
    EXPECT_EQ(back[i].point_source_id, cloud[i].point_source_id);
    EXPECT_EQ(back[i].gps_time, cloud[i].gps_time);
  }
}

// LAS 1.4: the 64-bit count wins when the legacy count is 0; two different non-zero counts fail.
TEST(LasIO, Las14LegacyAnd64BitPointCounts)
{
  pcl::PointCloud<PointLiDAR> cloud, back;
  std::vector<Eigen::Vector3d> truth;
  makeUtmCloud(20, 3, kBase, kOrigin, cloud, truth);
  io::SaveOptions so;
  so.las_minor_version = 4;  // format 3 in 1.4: both counts written
  std::vector<std::uint8_t> bytes;
  std::string error;
  ASSERT_TRUE(io::writeLas(cloud, kOrigin, bytes, error, so)) << error;
  EXPECT_EQ(at<std::uint32_t>(bytes, 107), 20u);
  EXPECT_EQ(at<std::uint64_t>(bytes, 247), 20u);
  io::CloudInfo info;
  set<std::uint32_t>(bytes, 107, 0);
  ASSERT_TRUE(io::readLas(bytes.data(), bytes.size(), back, info, error)) << error;
  EXPECT_EQ(back.size(), 20u);
  set<std::uint32_t>(bytes, 107, 19);
  EXPECT_FALSE(io::readLas(bytes.data(), bytes.size(), back, info, error));
  EXPECT_NE(error.find("point count mismatch"), std::string::npos) << error;
}

// VLRs pass through; the extra-bytes VLR is dropped because written records have none.
TEST(LasIO, VlrsAreWrittenAndRead)
{
  pcl::PointCloud<PointLiDAR> cloud, back;
  std::vector<Eigen::Vector3d> truth;
  makeUtmCloud(10, 1, kBase, kOrigin, cloud, truth);
  io::SaveOptions so;
  io::LasVlr crs{"LASF_Projection", 2112, "OGC WKT", {'P', 'R', 'O', 'J', 'C', 'S', 0}};
  io::LasVlr extra{"LASF_Spec", 4, "extra bytes", std::vector<std::uint8_t>(192, 0)};
  so.las_vlrs = {crs, extra};
  so.las_adjusted_standard_gps_time = true;
  std::vector<std::uint8_t> bytes;
  std::string error;
  ASSERT_TRUE(io::writeLas(cloud, kOrigin, bytes, error, so)) << error;
  io::CloudInfo info;
  ASSERT_TRUE(io::readLas(bytes.data(), bytes.size(), back, info, error)) << error;
  ASSERT_EQ(info.las.vlrs.size(), 1u);
  EXPECT_EQ(info.las.vlrs[0].user_id, "LASF_Projection");
  EXPECT_EQ(info.las.vlrs[0].record_id, 2112);
  EXPECT_EQ(info.las.vlrs[0].data, crs.data);
  EXPECT_EQ(info.las.offset_to_points, 227u + 54u + crs.data.size());
  EXPECT_EQ(info.las.global_encoding & 1, 1);
  EXPECT_EQ(back.size(), 10u);
}

// The writer refuses what the chosen format cannot hold instead of truncating it.
TEST(LasIO, WriterRefusesImpossibleCombinations)
{
  pcl::PointCloud<PointLiDAR> cloud;
  std::vector<Eigen::Vector3d> truth;
  makeUtmCloud(5, 6, kBase, kOrigin, cloud, truth);
  for (auto& p : cloud) {
    p.classification = 2;
    p.return_number = p.number_of_returns = 1;
  }
  cloud[2].classification = 64;  // IGN code: needs formats 6-10
  std::vector<std::uint8_t> bytes;
  std::string error;
  io::SaveOptions so;  // 1.2 / format 3
  EXPECT_FALSE(io::writeLas(cloud, kOrigin, bytes, error, so));
  EXPECT_NE(error.find("class 64"), std::string::npos) << error;
  so.las_point_format = 6;
  EXPECT_FALSE(io::writeLas(cloud, kOrigin, bytes, error, so));
  EXPECT_NE(error.find("needs LAS 1.4"), std::string::npos) << error;
  so.las_minor_version = 4;
  EXPECT_TRUE(io::writeLas(cloud, kOrigin, bytes, error, so)) << error;
  so.las_scale = Eigen::Vector3d::Constant(1e-9);  // 400 m / 1e-9 overflows int32
  EXPECT_FALSE(io::writeLas(cloud, kOrigin, bytes, error, so));
}
