// Runs pcl_ls3d_compare on a tiny generated, georeferenced pair: every method reports finite
// numbers, LS3D-LND recovers the known truth, and bad input exits non-zero without writing.
#include "io/tool_run.h"

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/synth/registration_pair.h>
#include <pcl_ls3d/synth/truth_json.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;
using namespace pcl_ls3d;

namespace {

const std::string kTool = std::string(PCL_LS3D_TOOL_DIR) + "/pcl_ls3d_compare";

/// Runs the tool; returns the exit code and fills `output` (stdout + stderr), written beside `log`.
int
run(const std::string& args, const fs::path& log, std::string& output)
{
  const pcl_ls3d_test::ToolRun r =
      pcl_ls3d_test::runToolMerged("pcl_ls3d_compare", args, log.parent_path().string());
  output = r.out;
  return r.code;
}

/// Runs the tool for its exit code alone.
int
run(const std::string& args)
{
  const fs::path scratch = fs::temp_directory_path() / ("pcl_ls3d_compare_run_" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  std::string ignored;
  const int code = run(args, scratch / "log", ignored);
  std::error_code ec;
  fs::remove_all(scratch, ec);
  return code;
}

/// The text table's row of `method` ("" if absent).
std::string
tableRow(const std::string& output, const std::string& method)
{
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind(method + " ", 0) == 0)
      return line;
  return "";
}

/// A 120 m × 120 m pair (≈14k source / 58k target points, 1 vs 4 pts/m², 70 % overlap, σ = 5 cm)
/// at UTM-like coordinates, so the tool's common local origin is exercised.
class CompareTool : public ::testing::Test
{
protected:
  static void
  SetUpTestSuite()
  {
    // One directory per process: CTest runs each test of this suite as its own process in
    // parallel, and a shared directory would be removed under a running sibling.
    dir_ = fs::temp_directory_path() / ("pcl_ls3d_compare_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    synth::RegistrationPairSettings s;
    s.seed = 3;
    s.size_x = s.size_y = 120.0;
    s.origin = Eigen::Vector3d(512000.0, 5402000.0, 250.0);
    const auto pair = synth::makeRegistrationPair(s);
    std::string error;
    ASSERT_TRUE(io::saveCloud((dir_ / "source.pcd").string(), *pair.source, pair.origin, error)) << error;
    ASSERT_TRUE(io::saveCloud((dir_ / "target.pcd").string(), *pair.target, pair.origin, error)) << error;
    ASSERT_TRUE(synth::writeTextFile((dir_ / "truth.json").string(), synth::truthJson(pair, s), true, error))
        << error;
  }
  static void
  TearDownTestSuite()
  {
    fs::remove_all(dir_);
  }
  std::string
  inputs() const
  {
    return (dir_ / "source.pcd").string() + " " + (dir_ / "target.pcd").string();
  }
  static fs::path dir_;
};
fs::path CompareTool::dir_;

}  // namespace

// All 7 methods run with finite figures; LS3D-LND converges with a mean displacement error below
// 5 cm. Bound: the initial misalignment is ~0.6 m (PCL-ICP ends near 0.5 m on this pair), so 5 cm
// fails any registration that did not work; on this small pair the 7 parameters (the scale above
// all) are weakly determined: measured 20–22 mm for seeds 3 and 7 (PCL-ICP-N: 24–30 mm).
TEST_F(CompareTool, AllMethodsWithTruth)
{
  if (!fs::exists(kTool))
    FAIL() << kTool << " not built";
  const fs::path out = dir_ / "result.json";
  fs::remove(out);
  ASSERT_EQ(run(inputs() + " -truth " + (dir_ / "truth.json").string() + " -json " + out.string()), 0);
  std::ifstream in(out);
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j["methods"].size(), 7u);
  EXPECT_TRUE(j["context"]["has_truth"].get<bool>());
  for (const auto& m : j["methods"]) {
    const std::string name = m["name"];
    SCOPED_TRACE(name);
    ASSERT_TRUE(m["ran"].get<bool>());
    EXPECT_TRUE(std::isfinite(m["time_s"].get<double>()));
    EXPECT_GT(m["iterations"].get<int>(), 0);
    ASSERT_FALSE(m["rms"].is_null());
    EXPECT_TRUE(std::isfinite(m["rms"].get<double>()));
    ASSERT_TRUE(m.contains("error"));
    for (const char* k : {"mean", "max", "max_bbox"}) {
      ASSERT_FALSE(m["error"][k].is_null()) << k;
      EXPECT_TRUE(std::isfinite(m["error"][k].get<double>())) << k;
    }
    EXPECT_EQ(m["error"]["parameters"].size(), 7u);
    for (const auto& row : m["transformation"])
      for (const auto& v : row)
        EXPECT_FALSE(v.is_null());
    if (name.rfind("LS3D", 0) == 0) {
      EXPECT_FALSE(m["sigma0"].is_null());
    }
    if (name == "LS3D-LND") {
      EXPECT_TRUE(m["converged"].get<bool>());
      EXPECT_LT(m["error"]["mean"].get<double>(), 0.05);
      EXPECT_LT(m["error"]["max"].get<double>(), 0.10);  // 2× the mean bound (lever arm)
    }
  }
}

// -methods selects a subset in table order; without -truth there is no "error" block.
TEST_F(CompareTool, MethodSubsetWithoutTruth)
{
  if (!fs::exists(kTool))
    FAIL() << kTool << " not built";
  const fs::path out = dir_ / "subset.json";
  fs::remove(out);
  ASSERT_EQ(run(inputs() + " -methods icp,ls3d-lnd -json " + out.string()), 0);
  std::ifstream in(out);
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j["methods"].size(), 2u);
  EXPECT_EQ(j["methods"][0]["name"], "LS3D-LND");
  EXPECT_EQ(j["methods"][1]["name"], "PCL-ICP");
  EXPECT_FALSE(j["methods"][0].contains("error"));
}

// Bad input exits non-zero: missing file, NaN-only file, unknown option, unknown method, bad
// truth, bad value, an output that is an input, an existing output without -overwrite.
TEST_F(CompareTool, BadInputFails)
{
  if (!fs::exists(kTool))
    FAIL() << kTool << " not built";
  const std::string src = (dir_ / "source.pcd").string();
  EXPECT_NE(run(src + " " + (dir_ / "missing.pcd").string()), 0);
  EXPECT_NE(run(inputs() + " -bogus"), 0);
  EXPECT_NE(run(inputs() + " -methods icp,foo"), 0);
  EXPECT_NE(run(inputs() + " -max_corr -1"), 0);
  EXPECT_NE(run(inputs() + " -iter 0"), 0);
  {
    std::ofstream nan_only(dir_ / "nan_only.xyz");
    nan_only << "nan nan nan\nnan nan nan\n";
  }
  EXPECT_NE(run((dir_ / "nan_only.xyz").string() + " " + (dir_ / "target.pcd").string()), 0);
  EXPECT_NE(run(src), 0);                          // one file only
  EXPECT_NE(run(inputs() + " -truth " + src), 0);  // not JSON
  {
    std::ofstream bad(dir_ / "bad_truth.json");
    bad << R"({"transformation": [[1,0,0],[0,1,0]]})";
  }
  EXPECT_NE(run(inputs() + " -truth " + (dir_ / "bad_truth.json").string()), 0);

  const auto size_before = fs::file_size(src);
  EXPECT_NE(run(inputs() + " -methods icp -json " + src + " -overwrite"), 0);
  EXPECT_EQ(fs::file_size(src), size_before);

  const fs::path existing = dir_ / "existing.json";
  {
    std::ofstream(existing) << "keep";
  }
  EXPECT_NE(run(inputs() + " -methods icp -json " + existing.string()), 0);
  std::ifstream in(existing);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "keep");
}

// A method that stops at its iteration limit has not converged, whatever PCL's hasConverged()
// says (true for ICP at the limit): with one iteration allowed, no method converges on this
// 0.6 m misalignment and the tool exits non-zero; PCL's rows have no trust verdict.
TEST_F(CompareTool, ExitsNonZeroWhenNoMethodConverges)
{
  if (!fs::exists(kTool))
    FAIL() << kTool << " not built";
  const fs::path out = dir_ / "one_iteration.json";
  fs::remove(out);
  EXPECT_NE(run(inputs() + " -methods ls3d-lnd,icp,gicp -iter 1 -json " + out.string()), 0);
  std::ifstream in(out);
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j["methods"].size(), 3u);
  for (const auto& m : j["methods"]) {
    SCOPED_TRACE(m["name"].get<std::string>());
    EXPECT_FALSE(m["converged"].get<bool>());
  }
  EXPECT_TRUE(j["methods"][1]["pcl_has_converged"].get<bool>());  // PCL-ICP at its limit
}

// Points on one line leave the point-to-plane normals undefined: PCL-ICP-N returns a NaN
// transformation with hasConverged() true. That is a failure, in the JSON and the exit status.
TEST_F(CompareTool, NonFiniteTransformationIsAFailure)
{
  if (!fs::exists(kTool))
    FAIL() << kTool << " not built";
  const fs::path a = dir_ / "line_a.xyz", b = dir_ / "line_b.xyz", out = dir_ / "line.json";
  {
    std::ofstream fa(a), fb(b);
    for (int i = 0; i < 2000; ++i) {
      const double t = 0.01 * i;
      fa << t << " " << 2 * t << " " << 3 * t << "\n";
      fb << t + 0.105 << " " << 2 * t + 0.01 << " " << 3 * t + 0.015 << "\n";
    }
  }
  fs::remove(out);
  EXPECT_NE(run(a.string() + " " + b.string() + " -methods icpn -json " + out.string()), 0);
  std::ifstream in(out);
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j["methods"].size(), 1u);
  const auto& m = j["methods"][0];
  bool finite = true;
  for (const auto& row : m["transformation"])
    for (const auto& v : row)
      finite = finite && !v.is_null();
  ASSERT_FALSE(finite) << "PCL-ICP-N no longer returns NaN on a line: the test needs another case";
  EXPECT_FALSE(m["converged"].get<bool>());
  EXPECT_EQ(m["stop"], "NaN");
}

// A run without an estimate (LS3D: 10 source points, TOO_FEW_OBSERVATIONS) has no RMS, σ0,
// errors or transformation: "-" in the table and null in the JSON, not the 0.00 of the
// identity it never moved from (the truth here is the identity).
TEST_F(CompareTool, FailedRunShowsNoFigures)
{
  if (!fs::exists(kTool))
    FAIL() << kTool << " not built";
  const fs::path src = dir_ / "few.xyz", tgt = dir_ / "grid.xyz", truth = dir_ / "ident.json";
  {
    std::ofstream fs_(src), ft(tgt), fj(truth);
    for (int i = 0; i < 40; ++i)
      for (int k = 0; k < 40; ++k)
        ft << i << " " << k << " " << 0.1 * std::sin(0.3 * i) * std::cos(0.2 * k) << "\n";
    for (int i = 0; i < 10; ++i)
      fs_ << 10 + i << " " << 15 + i << " " << 0.1 * std::sin(0.3 * (10 + i)) * std::cos(0.2 * (15 + i))
          << "\n";
    fj << R"({"transformation": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})";
  }
  const fs::path out = dir_ / "few.json";
  fs::remove(out);
  std::string text;
  run(src.string() + " " + tgt.string() + " -methods ls3d-lnd -truth " + truth.string() + " -json " +
          out.string(),
      dir_ / "few.log", text);
  const std::string row = tableRow(text, "LS3D-LND");
  ASSERT_NE(row.find("TOO_FEW"), std::string::npos) << text;
  // method iter time cpu conv stop trust, then RMS s0 mean max bbox | tx ty tz phi om ka m
  std::istringstream cells(row);
  std::vector<std::string> cell;
  for (std::string c; cells >> c;)
    cell.push_back(c);
  ASSERT_EQ(cell.size(), 20u) << row;
  for (std::size_t i = 7; i < cell.size(); ++i)
    EXPECT_TRUE(cell[i] == "-" || cell[i] == "|") << i << ": " << row;
  std::ifstream in(out);
  const auto j = nlohmann::json::parse(in);
  const auto& m = j["methods"][0];
  EXPECT_TRUE(m["rms"].is_null());
  EXPECT_TRUE(m["sigma0"].is_null());
  EXPECT_TRUE(m["error"].is_null());
  for (const auto& r : m["transformation"])
    for (const auto& v : r)
      EXPECT_TRUE(v.is_null());
}

// Lengths are labelled in the data's unit: the CRS's of a LAS input or one a PCD header records
// (international feet here), "units" without a CRS; never a fixed [m] / [mm]. The default
// lengths are metres, converted to that unit; lengths given are the data's.
TEST_F(CompareTool, UnitsFollowTheCrs)
{
  if (!fs::exists(kTool))
    FAIL() << kTool << " not built";
  io::SaveOptions feet;
  const std::string wkt = maps::crsFromUserInput("EPSG:2994");  // NAD83(CORS96) / Oregon Lambert (ft)
  ASSERT_EQ(maps::crsLinearUnitName(wkt), "ft");
  feet.las_vlrs = {maps::wktVlr(wkt)};
  for (const char* name : {"source", "target"}) {
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(io::loadCloud((dir_ / (std::string(name) + ".pcd")).string(), cloud, info, error));
    ASSERT_TRUE(
        io::saveCloud((dir_ / (std::string(name) + ".las")).string(), cloud, info.origin, error, feet))
        << error;
  }
  std::string text;
  run((dir_ / "source.las").string() + " " + (dir_ / "target.las").string() +
          " -methods icp -iter 2 -truth " + (dir_ / "truth.json").string(),
      dir_ / "ft.log", text);
  EXPECT_NE(text.find("RMS[ft]"), std::string::npos) << text;
  EXPECT_NE(text.find("mean[ft]"), std::string::npos) << text;
  // The default lengths are metres, converted: 2 m = 6.56168 ft, 1 m = 3.28084 ft.
  EXPECT_NE(text.find("PCL settings : max_corr=6.56168 ft"), std::string::npos) << text;
  EXPECT_NE(text.find("LS3D settings: max_corr=6.56168 ft"), std::string::npos) << text;
  EXPECT_NE(text.find("trans_eps=3.28084e-05 ft"), std::string::npos) << text;
  EXPECT_NE(text.find("NDT res=6.56168 ft step=1.64042 ft"), std::string::npos) << text;
  EXPECT_NE(text.find("within 3.28084 ft"), std::string::npos) << text;
  EXPECT_EQ(text.find("[m]"), std::string::npos) << text;
  EXPECT_EQ(text.find("[mm]"), std::string::npos) << text;
  // Lengths given are the data's unit.
  run((dir_ / "source.las").string() + " " + (dir_ / "target.las").string() +
          " -methods icp -iter 2 -max_corr 2 -ndt_res 2 -rms_dist 1",
      dir_ / "ft_given.log", text);
  EXPECT_NE(text.find("PCL settings : max_corr=2 ft"), std::string::npos) << text;
  EXPECT_NE(text.find("LS3D settings: max_corr=2 ft"), std::string::npos) << text;
  EXPECT_NE(text.find("NDT res=2 ft step=1.64042 ft"), std::string::npos) << text;
  EXPECT_NE(text.find("within 1 ft"), std::string::npos) << text;

  // The same clouds as PCDs that record the CRS in their header (as pcl_ls3d_convert writes them).
  io::SaveOptions pcd_feet;
  pcd_feet.crs_wkt = wkt;
  for (const char* name : {"source", "target"}) {
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(io::loadCloud((dir_ / (std::string(name) + ".las")).string(), cloud, info, error));
    ASSERT_TRUE(
        io::saveCloud((dir_ / (std::string(name) + "_ft.pcd")).string(), cloud, info.origin, error, pcd_feet))
        << error;
  }
  run((dir_ / "source_ft.pcd").string() + " " + (dir_ / "target_ft.pcd").string() + " -methods icp -iter 2",
      dir_ / "ft_pcd.log", text);
  EXPECT_NE(text.find("RMS[ft]"), std::string::npos) << text;

  run(inputs() + " -methods icp -iter 2", dir_ / "units.log", text);
  EXPECT_NE(text.find("RMS[units]"), std::string::npos) << text;
  EXPECT_EQ(text.find("[m]"), std::string::npos) << text;
  EXPECT_NE(text.find("max_corr=2 units"), std::string::npos) << text;  // without a CRS: as is
}

// A bad length says what is allowed, not the machine's double limits.
TEST_F(CompareTool, BadLengthSaysItMustBePositive)
{
  if (!fs::exists(kTool))
    FAIL() << kTool << " not built";
  std::string text;
  EXPECT_NE(run(inputs() + " -max_corr -1", dir_ / "neg.log", text), 0);
  EXPECT_NE(text.find("-max_corr must be > 0"), std::string::npos) << text;
  EXPECT_EQ(text.find("e+308"), std::string::npos) << text;
  EXPECT_NE(run(inputs() + " -thinning -1", dir_ / "neg.log", text), 0);
  EXPECT_NE(text.find("-thinning must be >= 0"), std::string::npos) << text;
}
