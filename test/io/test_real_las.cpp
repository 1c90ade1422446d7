/// \file test_real_las.cpp
/// \brief The real LAS files of shared/data load with the point counts, bounds and point-source
///        ids that shared/data/MANIFEST.md lists (values read independently with Python struct).

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/strip_tools.h>

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

using namespace pcl_ls3d;

namespace {

struct Expected
{
  const char* path;
  int minor, format;
  std::size_t points;
  Eigen::Vector3d min, max;
  std::map<std::uint16_t, std::size_t> strips;
};

// From MANIFEST.md, "LAS files: header facts, strips and classes" (bounds printed to 0.01).
const std::vector<Expected>&
expected()
{
  static const std::vector<Expected> files = {
      {"registration/pdal/autzen-thin.las",
       2,
       3,
       10653,
       {635589.01, 848886.45, 406.59},
       {638994.75, 853535.43, 593.73},
       {{7326, 453},
        {7327, 1272},
        {7328, 1477},
        {7329, 1635},
        {7330, 1362},
        {7331, 1488},
        {7332, 1611},
        {7333, 937},
        {7334, 418}}},
      {"registration/pdal/sample_c.las",
       2,
       3,
       14408,
       {674521.92, 1206740.08, 627.53},
       {674605.32, 1206814.96, 656.23},
       {{54, 7303}, {55, 398}, {56, 4308}, {58, 2399}}},
      {"registration/pdal/mvk-thin.las",
       2,
       1,
       6280,
       {2045001.76, 1267501.19, 95.79},
       {2049993.92, 1272499.79, 228.73},
       {{2003, 1751}, {2004, 2893}, {2005, 1636}}},
      {"registration/pdal/autzen-bmx-2010.las",
       4,
       7,
       829,
       {194472.82, 259222.19, 422.93},
       {194506.92, 259264.09, 434.51},
       {{7328, 809}, {7329, 20}}},
      {"registration/ign_lidarhd/las_with_origin_dsmMarker.las",
       4,
       8,
       67826,
       {949361.00, 6715402.00, 256.00},
       {949411.00, 6715452.00, 259.91},
       {{3025, 37809}, {3026, 30017}}},
      {"registration/ign_lidarhd/target_cloud_crop.las",
       4,
       7,
       9423,
       {961405.00, 6431680.00, 2545.47},
       {961418.00, 6431695.00, 2559.88},
       {{5280, 1467}, {5332, 1280}, {5333, 861}, {5340, 1107}, {5341, 977}, {5643, 2109}, {5646, 1622}}},
      {"registration/ign_lidarhd/test_semis_2023_0292_6833_LA93_IGN69.las",
       4,
       6,
       289055,
       {292000.00, 6832000.00, 43.30},
       {292999.98, 6832999.99, 107.61},
       {{0, 12}, {1, 20481}, {2, 99618}, {3, 122094}, {4, 46850}}},
      {"segmentation/ctview__test_data_77055_627760_LA93_IGN69.las",
       2,
       3,
       60653,
       {770550.00, 6277550.00, 20.72},
       {770600.00, 6277600.00, 39.62},
       {{706, 48617}, {707, 12036}}},
  };
  return files;
}

}  // namespace

TEST(RealLas, CountsBoundsAndStripsMatchTheManifest)
{
  const std::filesystem::path root(PCL_LS3D_SHARED_DATA_DIR);
  if (!std::filesystem::is_directory(root))
    GTEST_SKIP() << "shared data folder " << root << " is absent; real-data test skipped";
  for (const Expected& e : expected()) {
    SCOPED_TRACE(e.path);
    const std::string path = (root / e.path).string();
    if (!std::filesystem::exists(path)) {
      ADD_FAILURE() << "listed in MANIFEST.md but missing: " << path;
      continue;
    }
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(io::loadCloud(path, cloud, info, error)) << error;
    EXPECT_EQ(info.format, "las");
    EXPECT_EQ(info.las.version_minor, e.minor);
    EXPECT_EQ(info.las.point_format, e.format);
    EXPECT_EQ(cloud.size(), e.points);
    // MANIFEST prints 2 decimals: agree within half of that plus the LAS quantum.
    const double tol = 0.005 + info.las.scale.maxCoeff();
    EXPECT_LT((info.min_file - e.min).cwiseAbs().maxCoeff(), tol);
    EXPECT_LT((info.max_file - e.max).cwiseAbs().maxCoeff(), tol);
    // Local coordinates + origin reproduce the file bounds (double origin, float local).
    Eigen::Vector3f lo, hi;
    lo.setConstant(std::numeric_limits<float>::max());
    hi = -lo;
    for (const auto& p : cloud) {
      lo = lo.cwiseMin(p.getVector3fMap());
      hi = hi.cwiseMax(p.getVector3fMap());
    }
    EXPECT_LT((lo.cast<double>() + info.origin - info.min_file).cwiseAbs().maxCoeff(), 1e-3);
    EXPECT_LT((hi.cast<double>() + info.origin - info.max_file).cwiseAbs().maxCoeff(), 1e-3);
    std::map<std::uint16_t, std::size_t> strips;
    for (const auto& [id, indices] : io::splitByPointSource(cloud))
      strips[id] = indices.size();
    EXPECT_EQ(strips, e.strips);
  }
}

// The PF3 and PF7 copies of autzen_trim hold the same 110,000 points.
TEST(RealLas, Autzen12And14CopiesAgree)
{
  const std::filesystem::path root(PCL_LS3D_SHARED_DATA_DIR);
  const auto a = root / "registration/pdal/autzen_trim.las";
  const auto b = root / "registration/pdal/autzen_trim_7.las";
  if (!std::filesystem::exists(a) || !std::filesystem::exists(b))
    GTEST_SKIP() << "shared data folder " << root << " (autzen_trim*.las) is absent; skipped";
  pcl::PointCloud<PointLiDAR> ca, cb;
  io::CloudInfo ia, ib;
  std::string error;
  ASSERT_TRUE(io::loadCloud(a.string(), ca, ia, error)) << error;
  io::LoadOptions lo;
  lo.use_origin = true;
  lo.origin = ia.origin;
  ASSERT_TRUE(io::loadCloud(b.string(), cb, ib, error, lo)) << error;
  ASSERT_EQ(ca.size(), 110000u);
  ASSERT_EQ(cb.size(), ca.size());
  for (std::size_t i = 0; i < ca.size(); i += 97) {
    EXPECT_LT((ca[i].getVector3fMap() - cb[i].getVector3fMap()).norm(), 1e-3f);
    EXPECT_EQ(ca[i].classification, cb[i].classification);
    EXPECT_EQ(ca[i].point_source_id, cb[i].point_source_id);
    EXPECT_EQ(ca[i].gps_time, cb[i].gps_time);
  }
}

// Independent check of the writer: shared/data/tools/lasinfo.py (Python struct, written for the
// data folder, not by us) must read our LAS 1.2 PF3 and 1.4 PF6 files with the right version,
// format, count, and header bounds equal to the bounds of the records it decodes.
TEST(RealLas, IndependentPythonReaderAcceptsOurFiles)
{
  const std::filesystem::path script =
      std::filesystem::path(PCL_LS3D_SHARED_DATA_DIR) / "tools" / "lasinfo.py";
  if (!std::filesystem::exists(script) || std::system("python3 -c 'pass' > /dev/null 2>&1") != 0)
    GTEST_SKIP() << script << " or python3 is absent; skipped";
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("ls3d_lasinfo_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (const auto& [minor, format] : {std::pair<int, int>{2, 3}, {4, 6}}) {
    pcl::PointCloud<PointLiDAR> cloud;
    for (int i = 0; i < 200; ++i) {
      PointLiDAR p(0.37f * i, -0.11f * i, 0.05f * i);
      p.classification = static_cast<std::uint8_t>(i % 7);
      p.point_source_id = static_cast<std::uint16_t>(10 + i % 2);
      cloud.push_back(p);
    }
    io::SaveOptions so;
    so.las_minor_version = static_cast<std::uint8_t>(minor);
    so.las_point_format = static_cast<std::uint8_t>(format);
    const std::string las = (dir / ("f" + std::to_string(format) + ".las")).string();
    const std::string log = las + ".txt";
    std::string error;
    ASSERT_TRUE(io::saveCloud(las, cloud, {650000.0, 6860000.0, 100.0}, error, so)) << error;
    ASSERT_EQ(std::system(("python3 " + script.string() + " " + las + " > " + log).c_str()), 0);
    std::ifstream in(log);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("LAS 1." + std::to_string(minor) + "  point format " + std::to_string(format)),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("points 200  compressed=False"), std::string::npos) << text;
    EXPECT_NE(text.find("records read 200"), std::string::npos) << text;
    EXPECT_NE(text.find("point source IDs: 2 distinct"), std::string::npos) << text;
    // "header bounds min (a, b, c) max (d, e, f)" vs "data bounds min (a b c) max (d e f)"
    auto numbers = [&](const std::string& key) {
      std::string line = text.substr(text.find(key));
      line = line.substr(0, line.find('\n'));
      std::vector<double> v;
      for (char& c : line)
        if (c == '(' || c == ')' || c == ',')
          c = ' ';
      std::istringstream s(line.substr(line.find("min") + 3));
      std::string word;
      while (s >> word)
        if (word != "max")
          v.push_back(std::stod(word));
      return v;
    };
    const auto hdr = numbers("header bounds"), data = numbers("data bounds");
    ASSERT_EQ(hdr.size(), 6u) << text;
    ASSERT_EQ(data.size(), 6u) << text;
    for (int k = 0; k < 6; ++k)
      EXPECT_NEAR(hdr[k], data[k], 1e-3) << text;  // data bounds are printed with 3 decimals
  }
  std::filesystem::remove_all(dir);
}
