/// \file test_cloud_io.cpp
/// \brief loadCloud()/saveCloud(): UTM round trip to 1 mm through every writer, origin rules,
///        NaN handling, overwrite protection, isSameFile, format detection, strip tools.

#include <pcl_ls3d/evaluation/segments_file.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/pcd_io.h>
#include <pcl_ls3d/io/strip_tools.h>

#include "io/io_test_utils.h"

#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

using namespace pcl_ls3d;
using pcl_ls3d_test::TempDir;

namespace {

const Eigen::Vector3d kBase(512345.0, 5412345.0, 321.0);
const Eigen::Vector3d kOrigin(512000.0, 5412000.0, 0.0);

std::string
readText(const std::string& path, std::size_t n = 4096)
{
  std::ifstream in(path, std::ios::binary);
  std::string s(n, '\0');
  in.read(&s[0], static_cast<std::streamsize>(n));
  s.resize(static_cast<std::size_t>(in.gcount()));
  return s;
}

}  // namespace

class UtmRoundTrip : public ::testing::TestWithParam<std::tuple<std::string, bool>>
{};

// Whole-millimetre UTM coordinates written with a non-zero origin and read back with the auto
// origin must agree within 1 mm (the requirement); float rounding of local values < 400 m is 3e-5 m.
TEST_P(UtmRoundTrip, EveryWriterKeepsOneMillimetre)
{
  const std::string ext = std::get<0>(GetParam());
  const bool binary = std::get<1>(GetParam());
  pcl::PointCloud<PointLiDAR> cloud, back;
  std::vector<Eigen::Vector3d> truth;
  pcl_ls3d_test::makeUtmCloud(3000, 3, kBase, kOrigin, cloud, truth);
  TempDir dir("ls3d_utm");
  const std::string path = dir.file("cloud." + ext);
  io::SaveOptions so;
  so.binary = binary;
  std::string error;
  ASSERT_TRUE(io::saveCloud(path, cloud, kOrigin, error, so)) << error;
  if (ext == "pcd" || ext == "ply") {  // x stored in double, as required for a non-zero origin
    EXPECT_NE(readText(path).find(ext == "pcd" ? "SIZE 8 8 8" : "property double x"), std::string::npos);
  }
  io::CloudInfo info;
  ASSERT_TRUE(io::loadCloud(path, back, info, error)) << error;
  EXPECT_EQ(info.format, ext == "txt" ? "xyz" : ext);
  ASSERT_EQ(back.size(), cloud.size());
  EXPECT_GT(info.origin[0], 5e5);  // auto origin: rounded bbox centre
  double worst = 0.0;
  for (std::size_t i = 0; i < back.size(); ++i) {
    const Eigen::Vector3d xb = back[i].getVector3fMap().cast<double>() + info.origin;
    worst = std::max(worst, (xb - truth[i]).cwiseAbs().maxCoeff());
    EXPECT_EQ(back[i].classification, cloud[i].classification);
    EXPECT_EQ(back[i].point_source_id, cloud[i].point_source_id);
    EXPECT_EQ(back[i].return_number, cloud[i].return_number);
    EXPECT_EQ(back[i].number_of_returns, cloud[i].number_of_returns);
    EXPECT_EQ(back[i].intensity, cloud[i].intensity);
    EXPECT_NEAR(back[i].gps_time, cloud[i].gps_time, 1e-6);  // XYZ prints 6 decimals
  }
  EXPECT_LT(worst, 1e-3) << ext;
}

INSTANTIATE_TEST_SUITE_P(AllWriters, UtmRoundTrip,
                         ::testing::Values(std::make_tuple("las", true), std::make_tuple("pcd", true),
                                           std::make_tuple("pcd", false), std::make_tuple("ply", true),
                                           std::make_tuple("ply", false), std::make_tuple("xyz", false),
                                           std::make_tuple("txt", false)),
                         [](const auto& info) {
                           return std::get<0>(info.param) + (std::get<1>(info.param) ? "_binary" : "_ascii");
                         });

// A forced origin (second cloud of a pair) is used as given.
TEST(CloudIO, ForcedOriginIsUsed)
{
  pcl::PointCloud<PointLiDAR> cloud, back;
  std::vector<Eigen::Vector3d> truth;
  pcl_ls3d_test::makeUtmCloud(100, 1, kBase, kOrigin, cloud, truth);
  TempDir dir("ls3d_forced");
  std::string error;
  ASSERT_TRUE(io::saveCloud(dir.file("a.las"), cloud, kOrigin, error)) << error;
  io::LoadOptions lo;
  lo.use_origin = true;
  lo.origin = Eigen::Vector3d(512300.5, 5412300.25, 100.0);
  io::CloudInfo info;
  ASSERT_TRUE(io::loadCloud(dir.file("a.las"), back, info, error, lo)) << error;
  EXPECT_EQ(info.origin, lo.origin);
  EXPECT_NEAR(back[0].x + lo.origin[0], truth[0][0], 1e-4);
  EXPECT_NEAR(back[0].z + lo.origin[2], truth[0][2], 1e-4);
}

// A PCD of local floats that records its origin (pcl_ls3d_segment's SEGMENTS.pcd) is read in
// that frame, as a LAS file's offset is applied: the stored values come back unchanged as the
// local coordinates, the origin and the bounds are the file's; a forced origin moves the points.
TEST(CloudIO, RecordedPcdOriginIsTheLocalFrame)
{
  TempDir dir("ls3d_pcd_origin");
  const Eigen::Vector3d recorded(512000.25, 5412000.0, 0.1 + 0.2);  // not a short decimal
  std::ofstream(dir.file("s.pcd")) << "# .PCD v0.7\n"
                                   << io::pcdOriginLine(recorded) << "\n"
                                   << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                      "WIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n"
                                      "-1.1 2.7 0.3\n300.123 -401.9 12\n";
  pcl::PointCloud<PointLiDAR> back;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(io::loadCloud(dir.file("s.pcd"), back, info, error)) << error;
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(info.origin, recorded);  // %.17g: the double comes back exactly
  EXPECT_EQ(info.file_origin, recorded);
  EXPECT_EQ(back[0].x, -1.1f);
  EXPECT_EQ(back[1].y, -401.9f);
  EXPECT_EQ(back[1].z, 12.f);
  EXPECT_EQ(info.min_file, Eigen::Vector3d(-1.1, -401.9, 0.3) + recorded);  // ASCII: read in double

  io::LoadOptions forced;
  forced.use_origin = true;
  forced.origin = Eigen::Vector3d(512100.0, 5412000.0, 0.0);
  ASSERT_TRUE(io::loadCloud(dir.file("s.pcd"), back, info, error, forced)) << error;
  EXPECT_EQ(info.origin, forced.origin);
  EXPECT_EQ(info.file_origin, recorded);
  EXPECT_NEAR(back[1].x, 300.123 + recorded[0] - forced.origin[0], 1e-5);

  // An origin line that cannot be read would put the cloud in the wrong place: one error line.
  for (const char* bad :
       {"# pcl_ls3d origin 1 2", "# pcl_ls3d origin 1 2 nan", "# pcl_ls3d origin 1 2 3 4"}) {
    std::ofstream(dir.file("b.pcd")) << "# .PCD v0.7\n"
                                     << bad
                                     << "\nVERSION 0.7\nFIELDS x y z\n"
                                        "SIZE 4 4 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2 3\n";
    EXPECT_FALSE(io::loadCloud(dir.file("b.pcd"), back, info, error)) << bad;
    EXPECT_NE(error.find("'# pcl_ls3d origin' is not followed by three finite numbers"), std::string::npos)
        << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
  // A malformed origin line before a good one: the reader of SEGMENTS files agrees with
  // loadCloud (refused), and a zero origin is still a recorded one.
  std::ofstream(dir.file("m.pcd")) << "# .PCD v0.7\n# pcl_ls3d origin 1 2\n"
                                   << io::pcdOriginLine(recorded)
                                   << "\nVERSION 0.7\nFIELDS x y z\n"
                                      "SIZE 4 4 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2 3\n";
  Eigen::Vector3d from_segments;
  EXPECT_FALSE(io::loadCloud(dir.file("m.pcd"), back, info, error));
  EXPECT_FALSE(evaluation::readSegmentsOrigin(dir.file("m.pcd"), from_segments));
  std::ofstream(dir.file("z.pcd")) << "# .PCD v0.7\n"
                                   << io::pcdOriginLine(Eigen::Vector3d::Zero())
                                   << "\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                      "WIDTH 1\nPOINTS 1\nDATA ascii\n1 2 3\n";
  ASSERT_TRUE(io::loadCloud(dir.file("z.pcd"), back, info, error)) << error;
  EXPECT_TRUE(info.has_file_origin);
  pcl::PointCloud<pcl::PointXYZ> plain;
  plain.push_back(pcl::PointXYZ(1.f, 2.f, 3.f));
  ASSERT_EQ(pcl::io::savePCDFileASCII(dir.file("p.pcd"), plain), 0);
  ASSERT_TRUE(io::loadCloud(dir.file("p.pcd"), back, info, error)) << error;
  EXPECT_FALSE(info.has_file_origin);  // PCL's own PCD records none

  Eigen::Vector3d parsed;
  EXPECT_EQ(io::parsePcdOriginLine("# another comment", parsed), io::PcdOriginLine::NotOrigin);
  EXPECT_EQ(io::parsePcdOriginLine(io::pcdOriginLine(recorded), parsed), io::PcdOriginLine::Origin);
  EXPECT_EQ(parsed, recorded);
}

TEST(CloudIO, AutoOriginRule)
{
  EXPECT_EQ(io::chooseOrigin({-5, -5, 0}, {9999, 10, 3}), Eigen::Vector3d::Zero());
  EXPECT_EQ(io::chooseOrigin({5e5, 5e6, 10}, {5e5 + 101, 5e6 + 50, 20}),
            Eigen::Vector3d(500051.0, 5000025.0, 0.0));  // 50.5 rounds away from zero
  EXPECT_EQ(io::chooseOrigin({-20000, 0, 0}, {-10000, 1, 1})[0], -15000.0);
}

// NaN points of an organized PCD are dropped and counted; an all-NaN file is a clear error.
TEST(CloudIO, NonFinitePointsDroppedAndAllNanIsAnError)
{
  TempDir dir("ls3d_nan");
  pcl::PointCloud<pcl::PointXYZ> organized(3, 2);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < organized.size(); ++i)
    organized[i] = i % 2 ? pcl::PointXYZ(nan, nan, nan) : pcl::PointXYZ(float(i), 1.f, 2.f);
  organized.is_dense = false;
  pcl::io::savePCDFileBinary(dir.file("org.pcd"), organized);
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(io::loadCloud(dir.file("org.pcd"), cloud, info, error)) << error;
  EXPECT_EQ(info.points_in_file, 6u);
  EXPECT_EQ(info.points_dropped_nonfinite, 3u);
  EXPECT_EQ(cloud.size(), 3u);
  EXPECT_EQ(cloud.height, 1u);
  EXPECT_FLOAT_EQ(cloud[2].x, 4.f);

  for (auto& p : organized)
    p = pcl::PointXYZ(nan, nan, nan);
  pcl::io::savePCDFileBinary(dir.file("allnan.pcd"), organized);
  EXPECT_FALSE(io::loadCloud(dir.file("allnan.pcd"), cloud, info, error));
  EXPECT_NE(error.find("no finite points (all 6 points are NaN/inf)"), std::string::npos) << error;
  io::LoadOptions lo;
  lo.allow_empty = true;
  EXPECT_TRUE(io::loadCloud(dir.file("allnan.pcd"), cloud, info, error, lo));
  EXPECT_EQ(info.points_loaded, 0u);
}

// A PCL PCD with "label" (pcl::PointXYZL, as shared/data/tools/las2pcd_stats.py writes) fills
// classification; intensity comes from PointXYZI.
TEST(CloudIO, PclPointTypesMapLabelAndIntensity)
{
  TempDir dir("ls3d_pcl");
  pcl::PointCloud<pcl::PointXYZL> labelled;
  pcl::PointXYZL p;
  p.x = 1.f;
  p.y = 2.f;
  p.z = 3.f;
  p.label = 6;
  labelled.push_back(p);
  pcl::io::savePCDFileASCII(dir.file("l.pcd"), labelled);
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(io::loadCloud(dir.file("l.pcd"), cloud, info, error)) << error;
  EXPECT_EQ(cloud[0].classification, 6);
  EXPECT_FLOAT_EQ(cloud[0].z, 3.f);
}

// A SEGMENTS.pcd (header line io::kPcdSegmentsMarker) holds segment ids in "label": every
// reader of io::loadCloud() must not take them for classes (convert used to write them, clamped
// to a byte, as LAS classes). Its own "classification" field, the object classes, is read; the
// same file without the marker is an ordinary labelled PCD.
TEST(CloudIO, SegmentsFileLabelIsNoClass)
{
  TempDir dir("ls3d_segments_marker");
  pcl::PointCloud<pcl::PointXYZL> labelled;
  pcl::PointXYZL p;
  p.x = 1.f;
  p.y = 2.f;
  p.z = 3.f;
  p.label = 300;
  labelled.push_back(p);
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(labelled, blob);
  std::string error;
  const std::string marker = std::string(io::kPcdSegmentsMarker) + "\n";
  ASSERT_TRUE(io::savePcdBinaryWithOrigin(dir.file("s.pcd"), blob, Eigen::Vector3d::Zero(), marker, error))
      << error;
  ASSERT_TRUE(io::savePcdBinaryWithOrigin(dir.file("plain.pcd"), blob, Eigen::Vector3d::Zero(), "", error))
      << error;
  pcl::PCLPointCloud2 classed;  // label 300, and a classification byte 6
  pcl::toPCLPointCloud2(labelled, classed);
  pcl::PCLPointField f;
  f.name = "classification";
  f.offset = classed.point_step;
  f.datatype = pcl::PCLPointField::UINT8;
  f.count = 1;
  classed.fields.push_back(f);
  std::vector<std::uint8_t> data;
  data.insert(data.end(), classed.data.begin(), classed.data.end());
  data.push_back(6);
  classed.point_step += 1;
  classed.row_step = classed.point_step;
  classed.data = data;
  ASSERT_TRUE(io::savePcdBinaryWithOrigin(dir.file("c.pcd"), classed, Eigen::Vector3d::Zero(), marker, error))
      << error;

  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  ASSERT_TRUE(io::loadCloud(dir.file("s.pcd"), cloud, info, error)) << error;
  EXPECT_TRUE(info.segments_file);
  EXPECT_EQ(cloud[0].classification, 0);
  EXPECT_EQ(std::count(info.fields.begin(), info.fields.end(), "label"), 0);
  ASSERT_TRUE(io::loadCloud(dir.file("c.pcd"), cloud, info, error)) << error;
  EXPECT_TRUE(info.segments_file);
  EXPECT_EQ(cloud[0].classification, 6);
  ASSERT_TRUE(io::loadCloud(dir.file("plain.pcd"), cloud, info, error)) << error;
  EXPECT_FALSE(info.segments_file);
  EXPECT_EQ(cloud[0].classification, 255);  // clamped to the byte
  // The reader and the quick header check agree, also on a marker line ending in CRLF.
  ASSERT_TRUE(io::savePcdBinaryWithOrigin(dir.file("crlf.pcd"), blob, Eigen::Vector3d::Zero(),
                                          std::string(io::kPcdSegmentsMarker) + "\r\n", error))
      << error;
  ASSERT_TRUE(io::loadCloud(dir.file("crlf.pcd"), cloud, info, error)) << error;
  EXPECT_TRUE(info.segments_file);
  EXPECT_TRUE(pcl_ls3d::evaluation::isSegmentsFile(dir.file("crlf.pcd")));
  EXPECT_TRUE(pcl_ls3d::evaluation::isSegmentsFile(dir.file("s.pcd")));
  EXPECT_FALSE(pcl_ls3d::evaluation::isSegmentsFile(dir.file("plain.pcd")));
}

TEST(CloudIO, OverwriteProtectionAndSameFile)
{
  TempDir dir("ls3d_overwrite");
  pcl::PointCloud<PointLiDAR> cloud;
  cloud.push_back(PointLiDAR(1.f, 2.f, 3.f));
  std::string error;
  ASSERT_TRUE(io::saveCloud(dir.file("a.pcd"), cloud, Eigen::Vector3d::Zero(), error)) << error;
  EXPECT_FALSE(io::saveCloud(dir.file("a.pcd"), cloud, Eigen::Vector3d::Zero(), error));
  EXPECT_NE(error.find("exists already"), std::string::npos) << error;
  io::SaveOptions so;
  so.overwrite = true;
  EXPECT_TRUE(io::saveCloud(dir.file("a.pcd"), cloud, Eigen::Vector3d::Zero(), error, so)) << error;

  std::filesystem::create_symlink(dir.file("a.pcd"), dir.file("link.pcd"));
  EXPECT_TRUE(io::isSameFile(dir.file("a.pcd"), dir.file("link.pcd")));
  EXPECT_TRUE(io::isSameFile(dir.file("a.pcd"), dir.path.string() + "/./sub/../a.pcd"));
  EXPECT_TRUE(io::isSameFile(dir.file("new.las"), dir.path.string() + "/./new.las"));
  EXPECT_FALSE(io::isSameFile(dir.file("a.pcd"), dir.file("b.pcd")));
}

TEST(CloudIO, FormatDetectionAndWriterRefusals)
{
  TempDir dir("ls3d_detect");
  pcl::PointCloud<PointLiDAR> cloud, back;
  cloud.push_back(PointLiDAR(1.f, 2.f, 3.f));
  std::string error;
  io::CloudInfo info;
  // A LAS file with a misleading extension is recognised by its signature.
  ASSERT_TRUE(io::saveCloud(dir.file("a.las"), cloud, Eigen::Vector3d::Zero(), error)) << error;
  std::filesystem::copy_file(dir.file("a.las"), dir.file("a.dat"));
  ASSERT_TRUE(io::loadCloud(dir.file("a.dat"), back, info, error)) << error;
  EXPECT_EQ(info.format, "las");
  std::ofstream(dir.file("b.foo")) << "1 2 3\n";
  EXPECT_FALSE(io::loadCloud(dir.file("b.foo"), back, info, error));
  EXPECT_NE(error.find("unknown file type"), std::string::npos) << error;
  EXPECT_FALSE(io::loadCloud(dir.path.string(), back, info, error));
  EXPECT_NE(error.find("directory"), std::string::npos) << error;
  // Truncated PCD / PLY: the header's count is checked against the data, the caller gets one line.
  std::ofstream(dir.file("t.pcd")) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                      "COUNT 1 1 1\nWIDTH 10\nHEIGHT 1\nPOINTS 10\nDATA binary\nab";
  EXPECT_FALSE(io::loadCloud(dir.file("t.pcd"), back, info, error));
  EXPECT_NE(error.find("PCD header says 10 points, but only 2 bytes"), std::string::npos) << error;
  std::ofstream(dir.file("t.ply")) << "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\n"
                                      "property float y\nproperty float z\nend_header\n1 2 3\n";
  EXPECT_FALSE(io::loadCloud(dir.file("t.ply"), back, info, error));
  EXPECT_NE(error.find("PLY header says 5 vertex items"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);
  EXPECT_FALSE(io::saveCloud(dir.file("c.las7"), cloud, Eigen::Vector3d::Zero(), error));
  EXPECT_NE(error.find("cannot write"), std::string::npos) << error;
  EXPECT_FALSE(
      io::saveCloud(dir.file("c.pcd"), pcl::PointCloud<PointLiDAR>(), Eigen::Vector3d::Zero(), error));
  EXPECT_NE(error.find("empty cloud"), std::string::npos) << error;
}

// A file name with a newline or other control bytes (any byte but '/' and NUL is allowed) is
// shown with '?' in its place: reader and writer errors stay one line.
TEST(CloudIO, ControlBytesInFileNamesKeepErrorsOnOneLine)
{
  TempDir dir("ls3d_names");
  const std::string name = dir.file("two\nlines\r\x1b.pcd");
  std::ofstream(name) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                         "WIDTH 10\nHEIGHT 1\nPOINTS 10\nDATA binary\nab";
  pcl::PointCloud<PointLiDAR> cloud, back;
  cloud.push_back(PointLiDAR(1.f, 2.f, 3.f));
  io::CloudInfo info;
  std::string error;
  EXPECT_FALSE(io::loadCloud(name, back, info, error));
  EXPECT_NE(error.find("two?lines??.pcd: PCD header says 10 points"), std::string::npos) << error;
  EXPECT_FALSE(io::saveCloud(name, cloud, Eigen::Vector3d::Zero(), error));
  EXPECT_NE(error.find("two?lines??.pcd: exists already"), std::string::npos) << error;
  EXPECT_FALSE(io::saveCloud(dir.file("x.\n\t"), cloud, Eigen::Vector3d::Zero(), error));
  EXPECT_NE(error.find("cannot write '.?\?' files"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

TEST(StripTools, SplitByPointSourceAndFilterByClassification)
{
  pcl::PointCloud<PointLiDAR> cloud;
  const std::uint16_t ids[] = {706, 707, 706, 3, 707, 706};
  const std::uint8_t classes[] = {2, 6, 5, 2, 64, 6};
  for (int i = 0; i < 6; ++i) {
    PointLiDAR p(float(i), 0.f, 0.f);
    p.point_source_id = ids[i];
    p.classification = classes[i];
    cloud.push_back(p);
  }
  const auto strips = io::splitByPointSource(cloud);
  ASSERT_EQ(strips.size(), 3u);
  EXPECT_EQ(strips.at(3), (pcl::Indices{3}));
  EXPECT_EQ(strips.at(706), (pcl::Indices{0, 2, 5}));
  EXPECT_EQ(strips.at(707), (pcl::Indices{1, 4}));
  EXPECT_EQ(io::filterByClassification(cloud, {2, 6}), (pcl::Indices{0, 1, 3, 5}));
  EXPECT_EQ(io::filterByClassification(cloud, {2, 6}, false), (pcl::Indices{2, 4}));
  EXPECT_TRUE(io::filterByClassification(cloud, {9}).empty());
}
