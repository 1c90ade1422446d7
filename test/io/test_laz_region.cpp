/// \file test_laz_region.cpp
/// \brief Box queries (LoadOptions::region, LasRecordFile::open with a region): a COPC file
///        decodes only the nodes its box meets and returns exactly the records of the full
///        decode inside the box (boxes holding no point, one node, many, the whole extent); the
///        same query on a file's LAS and LAZ twins gives the same records; levels thin the
///        octree; PCD inputs are filtered; bad regions get one line. Real files skip when
///        shared/data is absent; generated files always run.

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/las_io.h>
#include <pcl_ls3d/io/las_records.h>

#include "io/io_test_utils.h"
#include "io/laz_test_utils.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

using namespace pcl_ls3d;
using pcl_ls3d_test::readBytes;
using pcl_ls3d_test::sharedData;

namespace {

using Records = std::vector<std::string>;  // one string per record, for sorted comparisons

/// The box test, written out here independently of the reader: file coordinates in double,
/// faces included.
bool
inside(const std::uint8_t* r, const io::LasHeaderInfo& h, const io::Region& region)
{
  for (int k = 0; k < (region.use_z ? 3 : 2); ++k) {
    std::int32_t q;
    std::memcpy(&q, r + 4 * k, 4);
    const double x = q * h.scale[k] + h.offset[k];
    if (x < region.box.min()[k] || x > region.box.max()[k])
      return false;
  }
  return true;
}

/// Every record of a LAS or LAZ file (decoded whole), and those inside `region` when given.
Records
allRecords(const std::string& path, io::LasHeaderInfo& h, const io::Region* region = nullptr)
{
  std::vector<std::uint8_t> bytes = readBytes(path), las;
  std::string error;
  EXPECT_TRUE(io::readLasHeader(bytes.data(), bytes.size(), h, error)) << error;
  if (h.laz.compressed) {
    EXPECT_TRUE(io::decompressLaz(bytes.data(), bytes.size(), las, error)) << error;
    bytes.swap(las);
  }
  io::LasHeaderInfo plain;
  const std::vector<std::uint8_t> r = pcl_ls3d_test::lasRecords(bytes, plain);
  Records out;
  for (std::size_t at = 0; at + plain.record_length <= r.size(); at += plain.record_length)
    if (!region || inside(r.data() + at, plain, *region))
      out.emplace_back(reinterpret_cast<const char*>(r.data() + at), plain.record_length);
  return out;
}

/// The records a region query gives (LasRecordFile::open with the region), and what it read.
Records
queried(const std::string& path, const io::Region& region, io::RegionInfo& read)
{
  io::LasRecordFile file;
  std::string error;
  EXPECT_TRUE(file.open(path, error, &region)) << error;
  read = file.regionInfo();
  Records out;
  for (std::size_t i = 0; i < file.size(); ++i)
    out.emplace_back(reinterpret_cast<const char*>(file.record(i)), file.header().record_length);
  return out;
}

Records
sorted(Records r)
{
  std::sort(r.begin(), r.end());
  return r;
}

io::Region
box2d(double x0, double y0, double x1, double y1)
{
  io::Region r;
  r.box = Eigen::AlignedBox3d(Eigen::Vector3d(x0, y0, 0.0), Eigen::Vector3d(x1, y1, 0.0));
  return r;
}

}  // namespace

// lone-star.copc.laz: each query returns exactly the records of the full decode in its box, and
// decodes fewer nodes than the file has unless the box covers it all.
TEST(LazRegion, CopcQueriesEqualTheFullDecodeInsideTheBox)
{
  const std::string path = sharedData("laz/pdal/lone-star.copc.laz");
  PCL_LS3D_REQUIRE_DATA(path);
  io::LasHeaderInfo h;
  allRecords(path, h);
  ASSERT_TRUE(h.copc.present);
  const Eigen::Vector3d lo = h.min, hi = h.max, mid = 0.5 * (lo + hi), size = hi - lo;
  struct Case
  {
    const char* name;
    io::Region region;
    bool empty, all_nodes;
  };
  io::Region slab3d;
  slab3d.box = Eigen::AlignedBox3d(lo, Eigen::Vector3d(hi.x(), hi.y(), lo.z() + 0.2 * size.z()));
  slab3d.use_z = true;
  const std::vector<Case> cases = {
      {"beside the extent", box2d(hi.x() + 10, hi.y() + 10, hi.x() + 20, hi.y() + 20), true, false},
      {"a small box", box2d(mid.x(), mid.y(), mid.x() + 0.02 * size.x(), mid.y() + 0.02 * size.y()), false,
       false},
      {"a quarter", box2d(lo.x(), lo.y(), mid.x(), mid.y()), false, false},
      {"a 3-D slab", slab3d, false, false},
      {"the whole extent", box2d(lo.x(), lo.y(), hi.x(), hi.y()), false, true},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    io::LasHeaderInfo full_header;
    const Records truth = sorted(allRecords(path, full_header, &c.region));
    io::RegionInfo read;
    const Records got = sorted(queried(path, c.region, read));
    EXPECT_EQ(got.size(), truth.size());
    EXPECT_TRUE(got == truth);
    EXPECT_EQ(truth.empty(), c.empty);
    EXPECT_TRUE(read.copc);
    EXPECT_EQ(read.nodes, h.copc.nodes);
    if (c.all_nodes) {
      EXPECT_EQ(read.nodes_read, read.nodes);
      EXPECT_EQ(truth.size(), h.point_count);
    } else {
      EXPECT_LT(read.nodes_read, read.nodes);
      EXPECT_LT(read.points_decoded, h.point_count);
    }
  }
}

// Levels: the root alone holds the root node's points; each level adds to the one above; the
// deepest level gives every point.
TEST(LazRegion, CopcLevelsThinTheOctree)
{
  const std::string path = sharedData("laz/pdal/lone-star.copc.laz");
  PCL_LS3D_REQUIRE_DATA(path);
  io::LasHeaderInfo h;
  const Records all = sorted(allRecords(path, h));
  ASSERT_TRUE(h.copc.present);
  ASSERT_GE(h.copc.levels.size(), 3u);
  io::Region region = box2d(h.min.x(), h.min.y(), h.max.x(), h.max.y());
  Records previous;
  std::uint64_t expected = 0;
  for (const io::CopcLevel& level : h.copc.levels) {
    SCOPED_TRACE("level " + std::to_string(level.level));
    region.max_level = level.level;
    io::RegionInfo read;
    const Records got = sorted(queried(path, region, read));
    expected += level.points;
    EXPECT_EQ(got.size(), expected);
    EXPECT_TRUE(std::includes(all.begin(), all.end(), got.begin(), got.end()));
    EXPECT_TRUE(std::includes(got.begin(), got.end(), previous.begin(), previous.end()));
    if (level.level == 0) {
      EXPECT_EQ(read.nodes_read, 1u);
    }
    previous = got;
  }
  EXPECT_TRUE(previous == all);
}

// The same box on a file's LAS twin and its LAZ gives the same records in the same order (both
// in file order); the COPC file of lone-star gives the same points as its LAZ (other format).
TEST(LazRegion, TwinsGiveTheSameRecords)
{
  const std::pair<const char*, const char*> twins[] = {
      {"registration/pdal/autzen_trim.las", "laz/pdal/autzen_trim.laz"},
      {"registration/ign_lidarhd/test_data_77055_627755_LA93_IGN69.las",
       "laz/ign/test_data_77055_627755_LA93_IGN69.laz"},
  };
  for (const auto& [las, laz] : twins) {
    SCOPED_TRACE(laz);
    PCL_LS3D_REQUIRE_DATA(sharedData(las));
    io::LasHeaderInfo h;
    allRecords(sharedData(laz), h);
    const Eigen::Vector3d mid = 0.5 * (h.min + h.max);
    const io::Region region = box2d(h.min.x(), h.min.y(), mid.x(), mid.y());
    io::RegionInfo read_las, read_laz;
    const Records a = queried(sharedData(las), region, read_las);
    const Records b = queried(sharedData(laz), region, read_laz);
    EXPECT_FALSE(a.empty());
    EXPECT_TRUE(a == b);
    EXPECT_FALSE(read_las.copc || read_laz.copc);
    EXPECT_EQ(read_laz.points_decoded, h.point_count);
  }
  // lone-star: PF1 pointwise LAZ against its PF6 COPC file; compare coordinates and time.
  const std::string laz = sharedData("laz/pdal/lone-star.laz");
  const std::string copc = sharedData("laz/pdal/lone-star.copc.laz");
  PCL_LS3D_REQUIRE_DATA(copc);
  io::LasHeaderInfo h;
  allRecords(laz, h);
  const Eigen::Vector3d mid = 0.5 * (h.min + h.max);
  io::LoadOptions options;
  options.region = box2d(mid.x() - 30, mid.y() - 30, mid.x() + 30, mid.y() + 30);
  options.use_origin = true;
  options.origin = mid.array().round();
  using Key = std::tuple<double, float, float, float>;  // time first: coordinates may round apart
  std::vector<Key> keys[2];
  for (int f = 0; f < 2; ++f) {
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(io::loadCloud(f ? copc : laz, cloud, info, error, options)) << error;
    EXPECT_EQ(info.points_loaded + info.points_outside_region, info.points_in_file);
    for (const PointLiDAR& p : cloud)
      keys[f].emplace_back(p.gps_time, p.x, p.y, p.z);
    std::sort(keys[f].begin(), keys[f].end());
  }
  EXPECT_GT(keys[0].size(), 100u);
  ASSERT_EQ(keys[0].size(), keys[1].size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < keys[0].size(); ++i)
    differ += std::get<0>(keys[0][i]) != std::get<0>(keys[1][i]) ||
              std::abs(std::get<1>(keys[0][i]) - std::get<1>(keys[1][i])) > 1e-3f ||
              std::abs(std::get<2>(keys[0][i]) - std::get<2>(keys[1][i])) > 1e-3f ||
              std::abs(std::get<3>(keys[0][i]) - std::get<3>(keys[1][i])) > 1e-3f;
  EXPECT_EQ(differ, 0u);
}

// Generated files (always run): LAS, LAZ and PCD answer a box query with the points of the
// cloud inside it, checked against the cloud's own coordinates.
TEST(LazRegion, GeneratedFilesAnswerTheSameQuery)
{
  pcl_ls3d_test::TempDir dir("ls3d_region");
  pcl::PointCloud<PointLiDAR> cloud;
  std::vector<Eigen::Vector3d> truth;
  const Eigen::Vector3d base(500100.0, 5000100.0, 50.0), origin(500000.0, 5000000.0, 0.0);
  pcl_ls3d_test::makeUtmCloud(3000, 6, base, origin, cloud, truth);
  std::string error;
  io::SaveOptions so;
  so.las_point_format = 6;
  so.las_minor_version = 4;
  for (const char* ext : {"las", "laz", "pcd"})
    ASSERT_TRUE(io::saveCloud(dir.file(std::string("cloud.") + ext), cloud, origin, error, so)) << error;
  io::Region region = box2d(base.x() - 300.5, base.y() - 250.25, base.x() + 150.0, base.y() + 20.0);
  region.use_z = true;
  region.box.min().z() = base.z() - 10.0;
  region.box.max().z() = base.z() + 5.0;
  std::size_t expected = 0;
  for (const Eigen::Vector3d& x : truth)
    expected += region.box.contains(x);
  ASSERT_GT(expected, 100u);
  ASSERT_LT(expected, truth.size());
  for (const char* ext : {"las", "laz", "pcd"}) {
    SCOPED_TRACE(ext);
    io::LoadOptions options;
    options.region = region;
    pcl::PointCloud<PointLiDAR> got;
    io::CloudInfo info;
    ASSERT_TRUE(io::loadCloud(dir.file(std::string("cloud.") + ext), got, info, error, options)) << error;
    EXPECT_EQ(got.size(), expected);
    EXPECT_EQ(info.points_outside_region, truth.size() - expected);
    EXPECT_TRUE(info.region.applied);
    for (const PointLiDAR& p : got) {
      const Eigen::Vector3d x = info.origin + p.getVector3fMap().cast<double>();
      EXPECT_TRUE(region.box.contains(x) || (region.box.exteriorDistance(x) < 1e-3)) << x.transpose();
    }
  }
}

// Bad regions and empty answers: one line each.
TEST(LazRegion, BadRegionsAndEmptyAnswers)
{
  pcl_ls3d_test::TempDir dir("ls3d_region_bad");
  pcl::PointCloud<PointLiDAR> cloud;
  std::vector<Eigen::Vector3d> truth;
  pcl_ls3d_test::makeUtmCloud(500, 3, {500100.0, 5000100.0, 50.0}, {500000.0, 5000000.0, 0.0}, cloud, truth);
  std::string error;
  for (const char* ext : {"las", "laz", "pcd"})
    ASSERT_TRUE(io::saveCloud(dir.file(std::string("c.") + ext), cloud, {500000.0, 5000000.0, 0.0}, error));
  const auto refuse = [&](const std::string& file, const io::Region& region, const char* expect,
                          bool allow_empty = false) {
    io::LoadOptions options;
    options.region = region;
    options.allow_empty = allow_empty;
    pcl::PointCloud<PointLiDAR> got;
    io::CloudInfo info;
    std::string why;
    EXPECT_FALSE(io::loadCloud(file, got, info, why, options)) << file;
    EXPECT_NE(why.find(expect), std::string::npos) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos);
  };
  io::Region inverted = box2d(10, 10, 0, 0);
  io::Region nan = box2d(0, 0, std::nan(""), 1);
  io::Region levelled = box2d(0, 0, 1e9, 1e9);
  levelled.max_level = 2;
  io::Region nothing = box2d(0, 0, 1, 1);
  for (const char* ext : {"las", "laz", "pcd"}) {
    const std::string file = dir.file(std::string("c.") + ext);
    refuse(file, inverted, "minimum exceeds its maximum");
    refuse(file, nan, "not finite");
    refuse(file, levelled, "needs a COPC file");
    refuse(file, nothing, "no point of the file lies inside the region");
    io::LoadOptions options;
    options.region = nothing;
    options.allow_empty = true;
    pcl::PointCloud<PointLiDAR> got;
    io::CloudInfo info;
    EXPECT_TRUE(io::loadCloud(file, got, info, error, options)) << error;
    EXPECT_TRUE(got.empty());
    EXPECT_EQ(info.points_outside_region, 500u);
  }
}
