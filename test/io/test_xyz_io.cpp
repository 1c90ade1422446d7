/// \file test_xyz_io.cpp
/// \brief ASCII XYZ variants: separators, comments, blank lines, header lines, column option,
///        extra columns, NaN rows, and the errors for malformed lines.

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/xyz_io.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

using namespace pcl_ls3d;

namespace {

bool
parse(const std::string& text, pcl::PointCloud<PointLiDAR>& cloud, io::CloudInfo& info, std::string& error,
      const io::LoadOptions& options = {})
{
  std::istringstream in(text);
  return io::readXyz(in, cloud, info, error, options);
}

}  // namespace

// Full UTM coordinates are parsed in double: after the shift the millimetres survive (a float
// parse would quantise a 5.4e6 northing to 0.5 m). Tolerance: float rounding of |local| < 1 m.
TEST(XyzIO, SpacesCommentsBlankLinesAndUtmPrecision)
{
  const std::string text = "# a comment\n"
                           "// another comment\n"
                           "\n"
                           "512345.678 5412345.679 321.001\n"
                           "   \t\n"
                           "512345.679\t5412345.680  321.002\r\n"
                           "512344.000 5412344.000 320.000\n";
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(parse(text, cloud, info, error)) << error;
  ASSERT_EQ(cloud.size(), 3u);
  EXPECT_EQ(info.origin, Eigen::Vector3d(512345.0, 5412345.0, 0.0));  // rounded bbox centre
  EXPECT_NEAR(cloud[0].x + info.origin[0], 512345.678, 1e-6);
  EXPECT_NEAR(cloud[0].y + info.origin[1], 5412345.679, 1e-6);
  EXPECT_NEAR(cloud[1].z + info.origin[2], 321.002, 2e-5);  // z not shifted: float half-ulp at 321 is 1.5e-5
  EXPECT_NEAR(info.min_file[0], 512344.0, 1e-9);
}

TEST(XyzIO, CommaSeparatedWithHeaderLineMapsNamedColumns)
{
  const std::string text = "X,Y,Z,Intensity,Classification,R,G,B\n"
                           "1.5,2.5,3.5,120,6,255,0,0\n"
                           "-1,-2,-3,40,2,0,255,0\n";
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(parse(text, cloud, info, error)) << error;
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_TRUE(info.origin.isZero());  // |coordinates| < 1e4: no shift
  EXPECT_FLOAT_EQ(cloud[0].x, 1.5f);
  EXPECT_FLOAT_EQ(cloud[1].z, -3.f);
  EXPECT_FLOAT_EQ(cloud[0].intensity, 120.f);
  EXPECT_EQ(cloud[0].classification, 6);
  EXPECT_EQ(cloud[1].classification, 2);
  EXPECT_EQ(info.fields, (std::vector<std::string>{"x", "y", "z", "intensity", "classification"}));
}

TEST(XyzIO, CommentedCloudCompareHeaderAndSemicolons)
{
  const std::string text = "//X;Y;Z;psid;gps_time\n1;2;3;706;12.25\n4;5;6;707;13.5\n";
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(parse(text, cloud, info, error)) << error;
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud[0].point_source_id, 706);
  EXPECT_EQ(cloud[1].gps_time, 13.5);
}

// Without a header only x y z are mapped; extra columns are ignored unless named by the option.
TEST(XyzIO, ExtraColumnsIgnoredByDefaultMappedByOption)
{
  const std::string text = "1 2 3 0.1 0.2 0.3 9\n4 5 6 0.4 0.5 0.6 2\n";
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(parse(text, cloud, info, error)) << error;
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud[0].classification, 0);
  EXPECT_EQ(info.fields.size(), 3u);
  EXPECT_EQ(info.xyz_unmapped_columns, 4u);

  io::LoadOptions options;
  options.xyz_columns = "x,y,z,_,_,skip,classification";
  ASSERT_TRUE(parse(text, cloud, info, error, options)) << error;
  EXPECT_EQ(cloud[0].classification, 9);
  EXPECT_EQ(cloud[1].classification, 2);

  // The option wins over a header line, which is then skipped.
  options.xyz_columns = "x,y,z,classification";
  ASSERT_TRUE(parse("x y z i\n1 2 3 4\n", cloud, info, error, options)) << error;
  ASSERT_EQ(cloud.size(), 1u);
  EXPECT_EQ(cloud[0].classification, 4);

  options.xyz_columns = "z,y,x";  // reordered columns
  ASSERT_TRUE(parse(text, cloud, info, error, options)) << error;
  EXPECT_FLOAT_EQ(cloud[0].x, 3.f);
  EXPECT_FLOAT_EQ(cloud[0].z, 1.f);
}

TEST(XyzIO, NonFiniteRowsAreDroppedAndCounted)
{
  const std::string text = "1 2 3\nnan 2 3\n4 inf 6\n7 8 9\n";
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(parse(text, cloud, info, error)) << error;
  EXPECT_EQ(info.points_in_file, 4u);
  EXPECT_EQ(info.points_loaded, 2u);
  EXPECT_EQ(info.points_dropped_nonfinite, 2u);
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_FLOAT_EQ(cloud[1].x, 7.f);
  EXPECT_TRUE(cloud.is_dense);
}

TEST(XyzIO, MalformedInputGivesALineNumber)
{
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  EXPECT_FALSE(parse("1 2 3\n4 5\n", cloud, info, error));
  EXPECT_NE(error.find("line 2: expected at least 3 columns, found 2"), std::string::npos) << error;
  EXPECT_FALSE(parse("1 2 3\n4 5 abc\n", cloud, info, error));
  EXPECT_NE(error.find("line 2, column 5: cannot parse 'abc'"), std::string::npos) << error;
  EXPECT_FALSE(parse("hello world\n1 2 3\n", cloud, info, error));
  EXPECT_NE(error.find("line 1"), std::string::npos) << error;
  io::LoadOptions options;
  options.xyz_columns = "x,y,height";
  EXPECT_FALSE(parse("1 2 3\n", cloud, info, error, options));
  EXPECT_NE(error.find("unknown XYZ column name 'height'"), std::string::npos) << error;
  options.xyz_columns = "x,y,intensity";
  EXPECT_FALSE(parse("1 2 3\n", cloud, info, error, options));
  EXPECT_NE(error.find("must name x, y and z"), std::string::npos) << error;
}

// An empty or comment-only file parses to 0 points (loadCloud turns that into an error).
TEST(XyzIO, CommentOnlyFileHasNoPoints)
{
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(parse("# nothing here\n\n", cloud, info, error)) << error;
  EXPECT_EQ(info.points_loaded, 0u);
  EXPECT_TRUE(cloud.empty());
}

// Issue 10 point 7: the writer keeps full precision. Every written x y z is the shortest text
// of the double x_local + origin (reading it back gives that double exactly), the local floats
// survive bit for bit through a file round trip with the same origin, and gps_time keeps its
// microseconds; SaveOptions::xyz_decimals asks for fixed decimals instead.
TEST(XyzIO, WriterKeepsFullPrecision)
{
  const Eigen::Vector3d origin(512000.0, 5412000.0, 0.0);
  pcl::PointCloud<PointLiDAR> cloud;
  for (int i = 0; i < 50; ++i) {
    PointLiDAR p(345.678f + 0.013f * static_cast<float>(i), 345.1234f - 0.7f * static_cast<float>(i),
                 321.00042f + 1e-3f * static_cast<float>(i));
    p.gps_time = 312345678.123456 + i;
    p.intensity = 1234.5f;
    cloud.push_back(p);
  }
  const std::string path = ::testing::TempDir() + "ls3d_xyz_precision.xyz";
  std::string error;
  io::SaveOptions so;
  so.overwrite = true;
  ASSERT_TRUE(io::saveCloud(path, cloud, origin, error, so)) << error;
  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  for (int i = 0; std::getline(in, line); ++i) {
    std::istringstream fields(line);
    double x, y, z, intensity, cls, psid, t;
    fields >> x >> y >> z >> intensity >> cls >> psid >> t;
    EXPECT_EQ(x, static_cast<double>(cloud[i].x) + origin[0]) << line;
    EXPECT_EQ(y, static_cast<double>(cloud[i].y) + origin[1]) << line;
    EXPECT_EQ(z, static_cast<double>(cloud[i].z) + origin[2]) << line;
    EXPECT_EQ(t, cloud[i].gps_time) << line;
  }
  pcl::PointCloud<PointLiDAR> back;
  io::CloudInfo info;
  io::LoadOptions lo;
  lo.use_origin = true;
  lo.origin = origin;
  ASSERT_TRUE(io::loadCloud(path, back, info, error, lo)) << error;
  ASSERT_EQ(back.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_EQ(back[i].x, cloud[i].x);
    EXPECT_EQ(back[i].y, cloud[i].y);
    EXPECT_EQ(back[i].z, cloud[i].z);
    EXPECT_EQ(back[i].gps_time, cloud[i].gps_time);
  }
  so.xyz_decimals = 3;
  ASSERT_TRUE(io::saveCloud(path, cloud, origin, error, so)) << error;
  std::ifstream again(path);
  std::getline(again, header);
  std::getline(again, line);
  EXPECT_EQ(line.rfind("512345.678 5412345.123 321.000 ", 0), 0u) << line;
  std::remove(path.c_str());
}
