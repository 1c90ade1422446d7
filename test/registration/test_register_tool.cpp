// pcl_ls3d_register end to end: a good run writes a JSON report with the documented keys and a
// transformation close to the truth; every bad input gives a non-zero exit and one error line.
#include "io/tool_run.h"
#include "ls3d_test_utils.h"

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/las_records.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace ls3d_test;

namespace {
struct ToolRun
{
  int code = 0;
  std::string output;
};

// stderr_only: capture the error stream alone (the tool reports progress on stdout).
ToolRun
runTool(const std::string& args, bool stderr_only = false)
{
  const fs::path scratch = fs::temp_directory_path() / ("ls3d_register_run_" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  const pcl_ls3d_test::ToolRun r =
      stderr_only ? pcl_ls3d_test::runTool("pcl_ls3d_register", args, scratch.string())
                  : pcl_ls3d_test::runToolMerged("pcl_ls3d_register", args, scratch.string());
  std::error_code ec;
  fs::remove_all(scratch, ec);
  return {r.code, stderr_only ? r.err : r.out};
}

int
errorLines(const std::string& out)
{
  int n = 0;
  std::size_t start = 0;
  while (start < out.size()) {
    const std::size_t end = out.find('\n', start);
    const std::string line = out.substr(start, end == std::string::npos ? std::string::npos : end - start);
    n += !line.empty();
    if (end == std::string::npos)
      break;
    start = end + 1;
  }
  return n;
}

class RegisterTool : public ::testing::Test
{
protected:
  void
  SetUp() override
  {
    if (!fs::exists(std::string(PCL_LS3D_TOOL_DIR) + "/pcl_ls3d_register"))
      FAIL() << "pcl_ls3d_register not built";
    dir_ = fs::temp_directory_path() / ("ls3d_tool_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    pair_ = smallPair(11, 80.0, 1.0, 1.0, 0.8, 0.02);
    const Eigen::Vector3d origin(500000.0, 5000000.0, 100.0);  // georeferenced input
    std::string error;
    ASSERT_TRUE(pcl_ls3d::io::saveCloud(path("source.pcd"), *pair_.source, origin, error)) << error;
    ASSERT_TRUE(pcl_ls3d::io::saveCloud(path("target.pcd"), *pair_.target, origin, error)) << error;
    truth_global_ = pcl_ls3d::localToGlobal(pair_.truth.matrix(), origin, origin);
    std::ofstream t(path("truth.json"));
    nlohmann::json j;
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < 4; ++r)
      rows.push_back({truth_global_(r, 0), truth_global_(r, 1), truth_global_(r, 2), truth_global_(r, 3)});
    j["transformation"] = rows;
    t << j.dump();
    std::ofstream(path("empty.pcd")) << "";
    std::ofstream(path("nan.pcd")) << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                      "COUNT 1 1 1\nWIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n"
                                      "POINTS 2\nDATA ascii\nnan nan nan\nnan nan nan\n";
    // The target 10 km away: no overlap.
    ASSERT_TRUE(pcl_ls3d::io::saveCloud(path("far.pcd"), *pair_.target,
                                        origin + Eigen::Vector3d(10000.0, 0.0, 0.0), error))
        << error;
  }
  void
  TearDown() override
  {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string
  path(const std::string& name) const
  {
    return (dir_ / name).string();
  }
  fs::path dir_;
  pcl_ls3d::synth::RegistrationPair pair_;
  Eigen::Matrix4d truth_global_;
};
}  // namespace

TEST_F(RegisterTool, GoodRunWritesReport)
{
  const ToolRun r = runTool(path("source.pcd") + " " + path("target.pcd") + " -json " + path("r.json") +
                            " -truth " + path("truth.json") + " -o " + path("aligned.pcd"));
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(path("r.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  for (const char* key : {"transformation", "converged", "iterations", "sigma0", "parameters", "sigmas",
                          "correlation", "observations_used", "local_origin"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_EQ(j["parameters"].size(), 7u);
  // The 4×4 maps SOURCE into TARGET in input (georeferenced) coordinates: compare with the
  // truth at a source point (2 cm noise: within 3 cm).
  Eigen::Matrix4d T;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      T(a, b) = j["transformation"][static_cast<std::size_t>(a)][static_cast<std::size_t>(b)].get<double>();
  const Eigen::Vector4d x(500010.0, 5000005.0, 102.0, 1.0);
  EXPECT_LT(((T - truth_global_) * x).head<3>().norm(), 0.03);
  EXPECT_NEAR(j["local_origin"][0].get<double>(), 500000.0, 100.0);
  EXPECT_TRUE(j.contains("truth_error"));
  EXPECT_TRUE(fs::exists(path("aligned.pcd")));
  // Refuses to overwrite without -overwrite.
  const ToolRun again = runTool(path("source.pcd") + " " + path("target.pcd") + " -json " + path("r.json"));
  EXPECT_NE(again.code, 0);
}

TEST_F(RegisterTool, BadInputGivesOneErrorLineAndNonZeroExit)
{
  const std::string s = path("source.pcd"), t = path("target.pcd");
  const std::vector<std::string> bad = {
      "",                              // no files
      s,                               // one file
      s + " " + path("missing.pcd"),   // missing target
      s + " " + path("empty.pcd"),     // empty file
      s + " " + t + " -rule nearest",  // unknown rule
      s + " " + t + " -params 5",      // impossible model
      s + " " + t + " -fix tx,psi",    // unknown parameter
      s + " " + t + " -fix \"\"",      // empty list
      s + " " + t + " -max_iter 0",    // impossible value
      s + " " + t + " -bogus 3",       // unknown option
      s + " " + t + " -o " + s,        // output would overwrite an input
      s + " " + t + " -truth " + path("missing.json"),
      s + " " + t + " -max_dist -1",  // no sentinel: a distance must be > 0
      s + " " + t + " -guess 0",
      // Outputs refused before any input is read (no "Loaded" line): a format without a writer,
      // a place no file can be created (/proc, even as root), a report there, a device.
      s + " " + t + " -o " + path("aligned.foo"),
      s + " " + t + " -o /proc/pcl_ls3d_aligned.xyz",
      s + " " + t + " -json /proc/pcl_ls3d_report.json",
      s + " " + t + " -o /dev/null -overwrite",
  };
  for (const std::string& args : bad) {
    const ToolRun r = runTool(args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_EQ(errorLines(r.output), 1) << args << "\n" << r.output;
  }
  // A symbolic link to a missing file is named as such (it said "File exists" before).
  std::filesystem::create_symlink(path("nowhere/aligned.pcd"), path("dangling.pcd"));
  for (const char* overwrite : {"", " -overwrite"}) {
    const ToolRun r = runTool(s + " " + t + " -o " + path("dangling.pcd") + overwrite);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_EQ(errorLines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("is a symbolic link to the missing"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("Loaded"), std::string::npos) << r.output;
  }
}

// Inputs that load but cannot be registered: NaN-only clouds and no overlap. Non-zero exit and
// exactly one line on stderr (the library's own PCL_ERROR is not repeated).
TEST_F(RegisterTool, NanOnlyAndNoOverlapGiveOneErrorLine)
{
  const std::string s = path("source.pcd"), t = path("target.pcd");
  for (const std::string& args :
       {s + " " + path("nan.pcd"), path("nan.pcd") + " " + t, s + " " + path("far.pcd")}) {
    const ToolRun r = runTool(args, true);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_EQ(errorLines(r.output), 1) << args << "\n" << r.output;
  }
  // A registration that found no estimate still writes its -json report: the reason for a
  // pipeline, no transformation.
  const ToolRun r = runTool(s + " " + path("far.pcd") + " -json " + path("failed.json"), true);
  EXPECT_EQ(r.code, 1) << r.output;
  std::ifstream in(path("failed.json"));
  ASSERT_TRUE(in.good());
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_FALSE(j["converged"].get<bool>());
  EXPECT_TRUE(j["transformation"].is_null());
  EXPECT_FALSE(j["message"].get<std::string>().empty());
  EXPECT_NE(r.output.find(j["termination"].get<std::string>()), std::string::npos) << r.output;
  // In a log holding both streams the error comes after the progress it follows (stdout is
  // line-buffered, not held back until exit).
  const ToolRun both = runTool(s + " " + path("far.pcd"));
  const std::size_t loaded = both.output.find("Loaded"), failed = both.output.find("registration failed");
  ASSERT_NE(loaded, std::string::npos) << both.output;
  ASSERT_NE(failed, std::string::npos) << both.output;
  EXPECT_LT(loaded, failed) << both.output;
}

// -classes 2 matches on the ground only: a source whose class-5 points (vegetation, 1–4 m above
// the ground, nothing like them in the target) would pull the fit still lands within 3 cm of
// the truth, the console says what was matched, and -o moves every point, class 5 included.
TEST_F(RegisterTool, ClassesSelectWhatIsMatchedAndOutputKeepsEveryPoint)
{
  Cloud source = *pair_.source, target = *pair_.target;
  for (auto& p : source)
    p.classification = 2;
  for (auto& p : target)
    p.classification = 2;
  const std::size_t ground = source.size();
  for (std::size_t k = 0; k < ground; k += 4) {  // a canopy over a quarter of the ground points
    PointT v = source[k];
    v.z += 1.0f + 3.0f * static_cast<float>(k % 7) / 7.0f;
    v.classification = 5;
    source.push_back(v);
  }
  const Eigen::Vector3d origin(500000.0, 5000000.0, 100.0);
  std::string error;
  ASSERT_TRUE(pcl_ls3d::io::saveCloud(path("veg_source.pcd"), source, origin, error)) << error;
  ASSERT_TRUE(pcl_ls3d::io::saveCloud(path("veg_target.pcd"), target, origin, error)) << error;
  const ToolRun r = runTool(path("veg_source.pcd") + " " + path("veg_target.pcd") + " -classes 2 -o " +
                            path("veg_aligned.pcd") + " -truth " + path("truth.json"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("Matching on classes 2: " + std::to_string(target.size()) + " of " +
                          std::to_string(target.size()) + " target and " + std::to_string(ground) + " of " +
                          std::to_string(source.size()) + " source points"),
            std::string::npos)
      << r.output;
  const std::size_t at = r.output.find("mean displacement ");
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_LT(std::stod(r.output.substr(at + 18)), 0.03) << r.output;
  pcl::PointCloud<PointT> written;
  pcl_ls3d::io::CloudInfo info;
  ASSERT_TRUE(pcl_ls3d::io::loadCloud(path("veg_aligned.pcd"), written, info, error)) << error;
  EXPECT_EQ(written.size(), source.size());
}

// -params 6 fixes m and -fix tz fixes tz exactly at the guess (identity); the report carries
// Qxx, the covariance behind the σ_i, the formal σ and one log record per iteration. The truth
// has a height offset, so holding tz at 0 leaves a misfit (σ0 ≈ 6 × the surfaces' noise): the
// quality gate says so with exit 3 and no -o cloud, and the JSON report is still complete.
TEST_F(RegisterTool, ParamsAndFixAreHonouredAndReportComplete)
{
  const ToolRun r = runTool(path("source.pcd") + " " + path("target.pcd") + " -params 6 -fix tz -json " +
                            path("fixed.json") + " -o " + path("fixed_aligned.pcd"));
  ASSERT_EQ(r.code, 3) << r.output;
  EXPECT_NE(r.output.find("registration not trustworthy"), std::string::npos) << r.output;
  EXPECT_FALSE(std::ifstream(path("fixed_aligned.pcd")).good());
  std::ifstream in(path("fixed.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["parameters"]["m"].get<double>(), 1.0);
  EXPECT_EQ(j["parameters"]["tz"].get<double>(), 0.0);
  EXPECT_TRUE(j["fixed"]["m"].get<bool>());
  EXPECT_TRUE(j["fixed"]["tz"].get<bool>());
  EXPECT_FALSE(j["fixed"]["tx"].get<bool>());
  EXPECT_EQ(j["sigmas"]["m"].get<double>(), 0.0);
  EXPECT_GT(j["sigmas"]["tx"].get<double>(), 0.0);
  EXPECT_GT(j["sigmas_formal"]["tx"].get<double>(), 0.0);
  EXPECT_EQ(j["qxx"].size(), 7u);
  const double var_tx = j["covariance"][0][0].get<double>();
  EXPECT_NEAR(var_tx, std::pow(j["sigmas"]["tx"].get<double>(), 2), 1e-12 * var_tx);
  EXPECT_EQ(j["log"].size(), j["iterations"].get<std::size_t>());
  EXPECT_EQ(j["termination"].get<std::string>(), "UNRELIABLE");
  EXPECT_FALSE(j["quality"]["trustworthy"].get<bool>());
  EXPECT_GT(j["quality"]["sigma0_ratio"].get<double>(), 3.0);
  EXPECT_EQ(j["redundancy"].get<long>(), j["observations_used"].get<long>() - 5);
}

// PDAL's Autzen thin-1 and thin-2 are the south and north of one georeferenced survey (truth:
// identity) and barely overlap at a few points per 100 ft². LS3D wanders 120 ft from the
// identity, with a position σ of 46 ft (2.9 × the surfaces' noise): the gate must refuse it
// (it was CONVERGED and "trustworthy" before the position test), while bun0 → bun4 (position σ
// 0.6 × the noise, a move 68 × its σ) stays trustworthy.
TEST(RegisterToolRealData, AMoveTheDataDoNotDetermineIsRefused)
{
  const std::string pdal = std::string(PCL_LS3D_SHARED_DATA_DIR) + "/registration/pdal/";
  const std::string pcl = std::string(PCL_LS3D_SHARED_DATA_DIR) + "/registration/pcl/";
  if (!std::ifstream(pdal + "thin-1.las").good() || !std::ifstream(pcl + "bun0.pcd").good())
    GTEST_SKIP() << "shared data not found under " << PCL_LS3D_SHARED_DATA_DIR << "; skipped";
  const std::string json =
      (std::filesystem::temp_directory_path() / ("pcl_ls3d_thin_" + std::to_string(::getpid()) + ".json"))
          .string();
  const ToolRun thin = runTool(pdal + "thin-1.las " + pdal + "thin-2.las -json " + json + " -overwrite");
  EXPECT_EQ(thin.code, 3) << thin.output;
  {
    std::ifstream in(json);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["termination"].get<std::string>(), "UNRELIABLE");
    const auto& q = j["quality"];
    EXPECT_GT(q["position_sigma"].get<double>(), 2.0 * q["expected_noise"].get<double>());
    EXPECT_LT(q["movement"].get<double>(), 3.0 * q["position_sigma"].get<double>());
  }
  const ToolRun bun = runTool(pcl + "bun0.pcd " + pcl + "bun4.pcd -json " + json + " -overwrite");
  EXPECT_EQ(bun.code, 0) << bun.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_TRUE(j["quality"]["trustworthy"].get<bool>());
  EXPECT_LT(j["quality"]["position_sigma"].get<double>(), j["quality"]["expected_noise"].get<double>());
  std::remove(json.c_str());
}

// A georeferenced LAS source written as LAS keeps its version, point format and VLRs (the CRS)
// byte for byte; every record is the input's moved by the reported 4x4 (to half the LAS scale).
// It was written as LAS 1.2 format 3 without any VLR.
TEST(RegisterToolRealData, LasOutputKeepsTheSourcesHeaderAndCrs)
{
  const std::string pdal = std::string(PCL_LS3D_SHARED_DATA_DIR) + "/registration/pdal/";
  if (!std::ifstream(pdal + "autzen_trim_7.las").good())
    GTEST_SKIP() << "shared data not found under " << PCL_LS3D_SHARED_DATA_DIR << "; skipped";
  const fs::path dir = fs::temp_directory_path() / ("pcl_ls3d_las_out_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string out = (dir / "aligned.las").string(), json = (dir / "r.json").string();
  const ToolRun r =
      runTool(pdal + "autzen_trim_7.las " + pdal + "autzen_trim.las -o " + out + " -json " + json);
  ASSERT_EQ(r.code, 0) << r.output;
  pcl_ls3d::io::LasRecordFile in, moved;
  std::string error;
  ASSERT_TRUE(in.open(pdal + "autzen_trim_7.las", error)) << error;
  ASSERT_TRUE(moved.open(out, error)) << error;
  const auto &a = in.header(), &b = moved.header();
  EXPECT_EQ(b.version_minor, a.version_minor);
  EXPECT_EQ(b.point_format, a.point_format);
  EXPECT_EQ(b.number_of_vlrs, a.number_of_vlrs);
  ASSERT_EQ(b.offset_to_points, a.offset_to_points);
  ASSERT_EQ(moved.size(), in.size());
  EXPECT_TRUE(
      std::equal(in.data() + a.header_size, in.data() + a.offset_to_points, moved.data() + b.header_size));
  std::ifstream js(json);
  const nlohmann::json j = nlohmann::json::parse(js);
  Eigen::Matrix4d T;
  for (int p = 0; p < 4; ++p)
    for (int q = 0; q < 4; ++q)
      T(p, q) = j["transformation"][static_cast<std::size_t>(p)][static_cast<std::size_t>(q)].get<double>();
  double worst = 0.0;
  for (std::size_t i = 0; i < in.size(); i += 97)
    worst = std::max(
        worst,
        ((T * in.coordinates(i).homogeneous()).head<3>() - moved.coordinates(i)).cwiseAbs().maxCoeff());
  EXPECT_LE(worst, 0.5 * b.scale.maxCoeff() + 1e-9);
  fs::remove_all(dir);
}

// -fix "" is refused with one line saying what is expected, not taken as "fix nothing".
TEST_F(RegisterTool, EmptyFixListIsRefused)
{
  const ToolRun r = runTool(path("source.pcd") + " " + path("target.pcd") + " -fix \"\"", true);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_EQ(errorLines(r.output), 1) << r.output;
  EXPECT_NE(r.output.find("-fix needs a comma list"), std::string::npos) << r.output;
}

// A thinning voxel far finer than the coordinates resolve keeps every source point: the voxel
// coordinates overflowed before and put every point into one voxel (1 point, TOO_FEW_...).
TEST_F(RegisterTool, ThinningFinerThanTheDataKeepsEveryPoint)
{
  const ToolRun r =
      runTool(path("source.pcd") + " " + path("target.pcd") + " -thin 1e-25 -json " + path("thin.json"));
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(path("thin.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["source_points_used"].get<std::size_t>(), pair_.source->size());
}

// Degenerate inputs fail, with their cause: two parallel lines, or coincident points, give the
// rule no surface to fit; that is not "no overlap" (the source lies over the target).
TEST_F(RegisterTool, DegenerateTargetIsNamedNotNoOverlap)
{
  {
    std::ofstream a(path("line.xyz")), b(path("line2.xyz")), c(path("same.xyz"));
    for (int i = 0; i < 2000; ++i) {
      const double t = 0.01 * i;
      a << t << " " << 2 * t << " " << 3 * t << "\n";
      b << t + 0.105 << " " << 2 * t + 0.01 << " " << 3 * t + 0.015 << "\n";
    }
    for (int i = 0; i < 100; ++i)
      c << "1 2 3\n";
  }
  const std::pair<std::string, std::string> cases[] = {
      {path("line.xyz") + " " + path("line2.xyz"), "collinear"},
      {path("same.xyz") + " " + path("same.xyz"), "coincident"}};
  for (const auto& [args, kind] : cases) {
    const ToolRun r = runTool(args, true);
    EXPECT_EQ(r.code, 1) << args;
    EXPECT_EQ(errorLines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("no surface the rule can fit"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(kind), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("no overlap"), std::string::npos) << r.output;
  }
}

// The error vs truth keeps its significant digits: a cloud matched to itself against a truth
// 2e-5 away reports 2e-05, not 0.0000.
TEST_F(RegisterTool, TruthErrorShowsSmallErrors)
{
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity();
  truth(0, 3) = 2e-5;
  {
    nlohmann::json j;
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < 4; ++r)
      rows.push_back({truth(r, 0), truth(r, 1), truth(r, 2), truth(r, 3)});
    j["transformation"] = rows;
    std::ofstream(path("tiny_truth.json")) << j.dump();
  }
  const ToolRun r =
      runTool(path("target.pcd") + " " + path("target.pcd") + " -truth " + path("tiny_truth.json"));
  const std::string key = "Error vs truth: mean displacement ";
  const std::size_t at = r.output.find(key);
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_NEAR(std::stod(r.output.substr(at + key.size())), 2e-5, 2e-6) << r.output;
}
