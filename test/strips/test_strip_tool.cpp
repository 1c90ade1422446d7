// pcl_ls3d_strip_adjust on a generated LAS block: corrected LAS strips keep every byte except
// X, Y, Z and the header bounds, their coordinates are the input's moved by the reported
// correction, and bad input (one strip, unknown reference, a split finding one strip, no
// overlap, LAZ, an output folder holding an input) gives one error line and a non-zero exit.
#include "../io/tool_json.h"
#include "../io/tool_run.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using pcl_ls3d_test::runTool;
using pcl_ls3d_test::slurp;

namespace {

template <typename T>
T
get(const std::string& bytes, std::size_t at)
{
  T v;
  std::memcpy(&v, bytes.data() + at, sizeof(T));
  return v;
}

struct LasLayout
{
  std::uint32_t offset = 0;  // to the point records
  std::uint16_t length = 0;  // of one record
  std::uint64_t count = 0;
  int format = 0;
  Eigen::Vector3d scale, origin;

  explicit LasLayout(const std::string& f)
  {
    offset = get<std::uint32_t>(f, 96);
    format = get<std::uint8_t>(f, 104) & 0x3f;
    length = get<std::uint16_t>(f, 105);
    count = get<std::uint32_t>(f, 107);
    if (count == 0 && get<std::uint8_t>(f, 25) >= 4)
      count = get<std::uint64_t>(f, 247);
    for (int a = 0; a < 3; ++a) {
      scale[a] = get<double>(f, 131 + 8 * static_cast<std::size_t>(a));
      origin[a] = get<double>(f, 155 + 8 * static_cast<std::size_t>(a));
    }
  }
  std::size_t
  record(std::uint64_t k) const
  {
    return offset + static_cast<std::size_t>(k) * length;
  }
  std::uint16_t
  psid(const std::string& f, std::uint64_t k) const
  {
    return get<std::uint16_t>(f, record(k) + (format >= 6 ? 20 : 18));
  }
  Eigen::Vector3d
  xyz(const std::string& f, std::uint64_t k) const
  {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a)
      p[a] = get<std::int32_t>(f, record(k) + 4 * static_cast<std::size_t>(a)) * scale[a] + origin[a];
    return p;
  }
};

class StripTool : public ::testing::Test
{
protected:
  static std::string dir;

  static void
  SetUpTestSuite()
  {
    dir = (fs::temp_directory_path() / ("pcl_ls3d_strip_tool_" + std::to_string(::getpid()))).string();
    fs::remove_all(dir);
    fs::create_directories(dir);
    // 3 strips of 240 m × 120 m, 30 % side overlap (36 m), 2 pts/m², strip 1 the identity.
    const auto r = runTool("pcl_ls3d_synth",
                           "strips -o '" + dir +
                               "/in' -format las -split -strips 3 -length 240 -swath 120 "
                               "-density 2 -seed 3 -shift_sigma 0.3 -angle_sigma 5e-4 -scale_sigma 0",
                           dir);
    ASSERT_EQ(r.code, 0) << r.err;
  }
  static void
  TearDownTestSuite()
  {
    fs::remove_all(dir);
  }
  static std::string
  in(const std::string& name)
  {
    return "'" + dir + "/in/" + name + "'";
  }
};
std::string StripTool::dir;

}  // namespace

TEST_F(StripTool, CorrectedLasKeepsEveryByteButXyzAndBounds)
{
  const auto r = runTool("pcl_ls3d_strip_adjust",
                         in("strips.las") + " -split psid -reference 1 -o '" + dir + "/out' -json '" + dir +
                             "/report.json' -maps '" + dir + "/maps'",
                         dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("CONVERGED"), std::string::npos) << r.out;
  const nlohmann::json report = nlohmann::json::parse(slurp(dir + "/report.json"));
  ASSERT_TRUE(report["converged"].get<bool>());
  ASSERT_EQ(report["strips"].size(), 3u);
  for (const char* map :
       {"mosaic_before.png", "mosaic_after.png", "mosaic_before.tif", "mosaic_after.tif", "histogram.png"})
    EXPECT_TRUE(fs::exists(dir + "/maps/" + map)) << map;

  const std::string input = slurp(dir + "/in/strips.las");
  const LasLayout lin(input);
  for (const auto& s : report["strips"]) {
    const int psid = s["point_source_id"].get<int>();
    const std::string path = dir + "/out/strips_psid" + std::to_string(psid) + ".las";
    ASSERT_TRUE(fs::exists(path)) << path;
    const std::string output = slurp(path);
    const LasLayout lout(output);
    ASSERT_EQ(lout.offset, lin.offset);
    ASSERT_EQ(lout.length, lin.length);
    ASSERT_EQ(lout.format, lin.format);
    // Header and VLRs: identical except the bounds (179..226) and the point counts (a split
    // output holds one flight line).
    for (std::size_t b = 0; b < lin.offset; ++b) {
      const bool bounds = b >= 179 && b < 227;
      const bool counts = (b >= 107 && b < 131) || (b >= 247 && b < 375);
      if (!bounds && !counts) {
        ASSERT_EQ(output[b], input[b]) << "header byte " << b;
      }
    }
    Eigen::Matrix4d T;
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 4; ++c)
        T(a, c) = s["transformation"][static_cast<std::size_t>(a)][static_cast<std::size_t>(c)].get<double>();
    if (s["reference"].get<bool>()) {
      EXPECT_TRUE(T.isIdentity(0.0));
    }
    std::uint64_t k_out = 0;
    double worst = 0.0;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for (std::uint64_t k = 0; k < lin.count; ++k) {
      if (lin.psid(input, k) != psid)
        continue;
      ASSERT_LT(k_out, lout.count);
      // Every byte after X, Y, Z is the input's, in input order.
      ASSERT_EQ(0, std::memcmp(output.data() + lout.record(k_out) + 12, input.data() + lin.record(k) + 12,
                               lin.length - 12u))
          << "record " << k;
      const Eigen::Vector3d moved = (T * lin.xyz(input, k).homogeneous()).head<3>();
      const Eigen::Vector3d written = lout.xyz(output, k_out);
      worst = std::max(worst, ((moved - written).array() / lin.scale.array()).abs().maxCoeff());
      lo = lo.cwiseMin(written);
      hi = hi.cwiseMax(written);
      ++k_out;
    }
    EXPECT_EQ(k_out, lout.count);
    EXPECT_LE(worst, 0.5 + 1e-6) << "coordinates off by more than half a LAS unit";
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(get<double>(output, 187 + 16 * static_cast<std::size_t>(a)), lo[a], 1e-9);  // min
      EXPECT_NEAR(get<double>(output, 179 + 16 * static_cast<std::size_t>(a)), hi[a], 1e-9);  // max
    }
  }
  // Never overwrites: a second run into the same folder fails before writing anything.
  const auto again =
      runTool("pcl_ls3d_strip_adjust", in("strips.las") + " -split psid -o '" + dir + "/out' -q", dir);
  EXPECT_NE(again.code, 0);
}

// A LAZ block comes back as LAZ: the corrected strips of strips.laz (pcl_ls3d_convert's lossless
// LAZ of strips.las) decode to exactly the records of the LAS run's corrected strips, header and
// VLRs included (the LASzip VLR aside).
TEST_F(StripTool, LazBlockComesBackAsLazWithTheLasRunsRecords)
{
  auto r = runTool("pcl_ls3d_convert", in("strips.las") + " " + in("strips.laz"), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* ext : {"las", "laz"}) {
    r = runTool("pcl_ls3d_strip_adjust",
                in(std::string("strips.") + ext) + " -split psid -reference 1 -q -o '" + dir + "/out_" + ext +
                    "'",
                dir);
    ASSERT_EQ(r.code, 0) << r.err;
  }
  std::size_t compared = 0;
  for (const auto& entry : fs::directory_iterator(dir + "/out_las")) {
    const std::string las_path = entry.path().string();
    const std::string laz_path = dir + "/out_laz/" + entry.path().stem().string() + ".laz";
    ASSERT_TRUE(fs::exists(laz_path)) << laz_path;
    const std::string laz = slurp(laz_path);
    ASSERT_NE(static_cast<std::uint8_t>(laz[104]) & 0x80, 0) << "not compressed: " << laz_path;
    // Decompressed by pcl_ls3d_convert: the LAS run's file byte for byte.
    const std::string back = dir + "/back_" + entry.path().filename().string();
    r = runTool("pcl_ls3d_convert", "'" + laz_path + "' '" + back + "'", dir);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(slurp(back) == slurp(las_path)) << laz_path;
    ++compared;
  }
  EXPECT_EQ(compared, 3u);
}

TEST_F(StripTool, BadInputGivesOneErrorLine)
{
  // A LAZ file: the compression bit of the point-format byte set.
  {
    std::string las = slurp(dir + "/in/strip_1.las");
    las[104] = static_cast<char>(las[104] | 0x80);
    std::ofstream(dir + "/in/strip_1.laz", std::ios::binary) << las;
  }
  const std::vector<std::pair<std::string, std::string>> cases = {
      {in("strip_1.las"), "one strip only"},
      {in("strips.las") + " -split psid -reference 99", "unknown reference"},
      {in("strip_1.las") + " -split psid", "one flight line"},
      {in("strip_1.las") + " " + in("strip_3.las"), "no overlap"},
      {in("strip_1.laz") + " " + in("strip_2.las"), "LAZ"},
      {in("strip_1.las") + " " + in("strip_2.las") + " -o '" + dir + "/in'", "holds the input"},
  };
  for (const auto& c : cases) {
    const auto r = runTool("pcl_ls3d_strip_adjust", c.first + " -q", dir);
    EXPECT_NE(r.code, 0) << c.second;
    EXPECT_EQ(pcl_ls3d_test::lineCount(r.err), 1u) << c.second << ":\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << c.second << ":\n" << r.out;
  }
}

// Outputs are checked before any input is read: the same input twice, a report or an output
// folder that cannot be written (/proc takes no file, even as root), a report named like a
// corrected strip. One error line each, nothing written, the inputs untouched.
TEST_F(StripTool, OutputsAndDuplicatesAreRefusedBeforeAnyWork)
{
  const std::string both = in("strip_1.las") + " " + in("strip_2.las");
  fs::create_directories(dir + "/outj");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {in("strip_1.las") + " " + in("strip_1.las"), "is given twice"},
      {both + " -json /proc/pcl_ls3d_report.json", "cannot write /proc/pcl_ls3d_report.json"},
      {both + " -o /proc/pcl_ls3d_out", "cannot create or write the folder /proc/pcl_ls3d_out"},
      {both + " -maps /proc/pcl_ls3d_maps", "cannot create or write the folder /proc/pcl_ls3d_maps"},
      {both + " -o '" + dir + "/outj' -json '" + dir + "/outj/strip_1.las'",
       "would replace the corrected strip"},
  };
  for (const auto& c : cases) {
    const auto r = runTool("pcl_ls3d_strip_adjust", c.first + " -q", dir);
    EXPECT_EQ(r.code, 1) << c.first;
    EXPECT_EQ(pcl_ls3d_test::lineCount(r.err), 1u) << c.first << ":\n" << r.err;
    EXPECT_NE(r.err.find(c.second), std::string::npos) << c.first << ":\n" << r.err;
  }
  EXPECT_TRUE(fs::is_empty(dir + "/outj"));
}

// No observation at all (a class no point has) is said as such, not as a singular geometry,
// and the overlap's row shows no figures that read as a perfect fit.
TEST_F(StripTool, NoObservationIsNamedAsTheCause)
{
  const auto r =
      runTool("pcl_ls3d_strip_adjust", in("strip_1.las") + " " + in("strip_2.las") + " -classes 99", dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.out.find("TOO_FEW_OBSERVATIONS"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no overlap has an observation"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("SINGULAR"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no observation (0 conjugate points"), std::string::npos) << r.out;
  // More observed points asked per direction than the overlap has: nothing is matched either,
  // and the message names the option.
  const auto few = runTool("pcl_ls3d_strip_adjust",
                           in("strip_1.las") + " " + in("strip_2.las") + " -min_obs 100000000", dir);
  EXPECT_EQ(few.code, 2) << few.err;
  EXPECT_NE(few.out.find("no overlap direction has 100000000 observed points (-min_obs)"), std::string::npos)
      << few.out;
}

// -one_way observes each overlap in one direction: about half the observations of both ways.
TEST_F(StripTool, OneWayHalvesTheObservations)
{
  const std::string both = in("strip_1.las") + " " + in("strip_2.las");
  const auto two = runTool("pcl_ls3d_strip_adjust", both + " -q -json '" + dir + "/two.json'", dir);
  const auto one = runTool("pcl_ls3d_strip_adjust", both + " -q -one_way -json '" + dir + "/one.json'", dir);
  ASSERT_EQ(two.code, 0) << two.out << two.err;
  ASSERT_EQ(one.code, 0) << one.out << one.err;
  const auto observations = [this](const std::string& name) {
    return pcl_ls3d_test::readJson(dir + "/" + name).at("overlaps").at(0).at("observations").get<double>();
  };
  const double n_two = observations("two.json"), n_one = observations("one.json");
  EXPECT_GT(n_one, 0.3 * n_two);
  EXPECT_LT(n_one, 0.7 * n_two);
}

// IGN's 1 km test_semis_2023 block (0.3 pts/m²): the adjustment moves strip 1 by 0.61 m
// (three times the strips' own noise) while the discrepancies' σMAD grows on 4 of its 5
// overlaps; that is UNRELIABLE, exit 3, not CONVERGED. The five 50 m IGN tiles, whose
// corrections do reduce the discrepancies, stay CONVERGED.
TEST(StripToolRealData, CorrectionsTheDiscrepanciesDoNotConfirmAreUnreliable)
{
  const std::string ign = std::string(PCL_LS3D_SHARED_DATA_DIR) + "/registration/ign_lidarhd/";
  if (!std::ifstream(ign + "test_semis_2023_0292_6833_LA93_IGN69.las").good())
    GTEST_SKIP() << "shared data not found under " << PCL_LS3D_SHARED_DATA_DIR << "; skipped";
  const std::string tmp = fs::temp_directory_path().string();
  const auto semis = runTool("pcl_ls3d_strip_adjust",
                             "'" + ign + "test_semis_2023_0292_6833_LA93_IGN69.las' -split psid", tmp);
  EXPECT_EQ(semis.code, 3) << semis.out << semis.err;
  EXPECT_NE(semis.out.find("UNRELIABLE"), std::string::npos) << semis.out;
  EXPECT_NE(semis.out.find("NOT CONFIRMED"), std::string::npos) << semis.out;
  std::string tiles;
  for (const char* t : {"77050_627755", "77050_627760", "77055_627755", "77055_627760", "77060_627760"})
    tiles += " '" + ign + "test_data_" + t + "_LA93_IGN69.las'";
  const auto five = runTool("pcl_ls3d_strip_adjust", tiles + " -split psid", tmp);
  EXPECT_EQ(five.code, 0) << five.out << five.err;
  EXPECT_NE(five.out.find("CONVERGED"), std::string::npos) << five.out;
}

// Option errors name the option the user typed and a range a user reads (no field names of the
// settings, no machine limits).
TEST_F(StripTool, OptionErrorsNameTheOption)
{
  const std::string both = in("strip_1.las") + " " + in("strip_2.las");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {" -max_iter 0", "-max_iter expects an integer in [1, 1000000], got '0'"},
      {" -max_obs 5", "-max_obs expects an integer >= 10, got '5'"},
      {" -max_dist -5", "-max_dist must be > 0"},
      {" -min_area -1", "-min_area expects a number >= 0, got '-1'"},
      {" -min_obs 0", "-min_obs expects an integer >= 1, got '0'"},
      {" -min_obs 5x", "-min_obs expects an integer >= 1, got '5x'"},
  };
  for (const auto& c : cases) {
    const auto r = runTool("pcl_ls3d_strip_adjust", both + c.first + " -q", dir);
    EXPECT_EQ(r.code, 1) << c.first;
    EXPECT_EQ(pcl_ls3d_test::lineCount(r.err), 1u) << c.first << ":\n" << r.err;
    EXPECT_NE(r.err.find(c.second), std::string::npos) << c.first << ":\n" << r.err;
  }
}

// Two IGN tiles that do not touch, each holding two flight lines: without -split the files do not
// overlap, and the error says how each line becomes a strip.
TEST(StripToolRealData, FilesOfSeveralFlightLinesGetTheSplitHint)
{
  const std::string ign = std::string(PCL_LS3D_SHARED_DATA_DIR) + "/registration/ign_lidarhd/";
  if (!std::ifstream(ign + "test_data_77050_627755_LA93_IGN69.las").good())
    GTEST_SKIP() << "shared data not found under " << PCL_LS3D_SHARED_DATA_DIR << "; skipped";
  const auto r = runTool("pcl_ls3d_strip_adjust",
                         "'" + ign + "test_data_77050_627755_LA93_IGN69.las' '" + ign +
                             "test_data_77060_627760_LA93_IGN69.las' -q",
                         fs::temp_directory_path().string());
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("no two strips overlap"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("-split psid makes each a strip"), std::string::npos) << r.err;
}
