// pcl_ls3d_deformation end to end on Li's surface (known truth and planted deformation): the
// JSON report's transformation is the truth, the residual cloud has one record per epoch point
// in order with the documented fields, and bad input gives one error line and a non-zero exit.
#include "../io/tool_json.h"
#include "../io/tool_run.h"
#include "li_surface_pair.h"

#include <pcl_ls3d/deformation/point_residual.h>
#include <pcl_ls3d/estimators/robust_matching.h>
#include <pcl_ls3d/evaluation/transform_error.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/maps/geotiff_io.h>
#include <pcl_ls3d/maps/png_io.h>
#include <pcl_ls3d/synth/li_surface.h>

#include <pcl/io/pcd_io.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace pcl_ls3d;
using pcl_ls3d_test::jsonMatrix;
using pcl_ls3d_test::lineCount;
using pcl_ls3d_test::readJson;
using pcl_ls3d_test::runTool;

namespace {

struct Scratch
{
  Scratch()
  {
    dir = fs::temp_directory_path() / ("pcl_ls3d_deformation_tool_" + std::to_string(::getpid()));
    fs::create_directories(dir);
  }
  ~Scratch()
  {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string
  file(const std::string& name) const
  {
    return (dir / name).string();
  }
  fs::path dir;
};

/// Li's surface with `percent` of the nodes raised by N(c σ, σ) at `position`, written as
/// s/ref.pcd (binary) and s/epoch.pcd (ASCII), as a user's files would come.
synth::LiSurface
writeLiPair(const Scratch& s, double percent, double c, synth::DeformationPosition position)
{
  synth::LiSurfaceSettings ls;
  ls.deformation_percent = percent;
  ls.deformation_c = c;
  ls.position = position;
  synth::LiSurface li = synth::makeLiSurface(ls);
  pcl::PointCloud<pcl::PointXYZ> ref, mate;
  pcl::copyPointCloud(*li.reference, ref);
  pcl::copyPointCloud(*li.mate, mate);
  EXPECT_EQ(pcl::io::savePCDFileBinary(s.file("ref.pcd"), ref), 0);
  EXPECT_EQ(pcl::io::savePCDFileASCII(s.file("epoch.pcd"), mate), 0);
  return li;
}

/// Li's pair moved to projected-like coordinates (UTM easting, northing, height), written as text
/// in double as survey files come; returns the epoch's points in those coordinates.
std::vector<Eigen::Vector3d>
writeLiPairAtUtm(const Scratch& s)
{
  synth::LiSurfaceSettings ls;
  ls.deformation_percent = 20.0;
  ls.deformation_c = 10.0;
  const synth::LiSurface li = synth::makeLiSurface(ls);
  const Eigen::Vector3d offset(500000.0, 5000000.0, 100.0);
  std::vector<Eigen::Vector3d> epoch;
  for (const auto& [cloud, name] :
       {std::make_pair(li.reference, "ref.xyz"), std::make_pair(li.mate, "epoch.xyz")}) {
    std::ofstream out(s.file(name));
    out.precision(17);
    for (const auto& p : *cloud) {
      const Eigen::Vector3d q = p.getVector3fMap().cast<double>() + offset;
      out << q.x() << " " << q.y() << " " << q.z() << "\n";
      if (cloud == li.mate)
        epoch.push_back(q);
    }
  }
  return epoch;
}

Eigen::Vector3d
jsonVector(const nlohmann::json& v)
{
  return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
}

/// Largest distance between A(p) and B(p) over `points`.
double
largestDifference(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B,
                  const std::vector<Eigen::Vector3d>& points)
{
  double worst = 0.0;
  for (const Eigen::Vector3d& p : points)
    worst = std::max(worst, ((A - B) * p.homogeneous()).head<3>().norm());
  return worst;
}

/// A small Li reference surface (20 × 20 grid) saved as ref.pcd in the scratch folder.
pcl::PointCloud<pcl::PointXYZ>
smallReference(const Scratch& s)
{
  synth::LiSurfaceSettings ls;
  ls.grid_size = 20;
  const synth::LiSurface li = synth::makeLiSurface(ls);
  pcl::PointCloud<pcl::PointXYZ> ref;
  pcl::copyPointCloud(*li.reference, ref);
  if (pcl::io::savePCDFileBinary(s.file("ref.pcd"), ref) != 0)
    ref.clear();
  return ref;
}

}  // namespace

TEST(DeformationTool, FindsTruthAndWritesResidualsInEpochOrder)
{
  const Scratch s;
  const synth::LiSurface li = writeLiPair(s, 20.0, 10.0, synth::DeformationPosition::LOWER_RIGHT);

  const auto run =
      runTool("pcl_ls3d_deformation",
              s.file("ref.pcd") + " " + s.file("epoch.pcd") + " -o " + s.file("res.pcd") + " -json " +
                  s.file("report.json") + " -map " + s.file("map") + " -crs EPSG:26917",
              s.dir.string());
  ASSERT_EQ(run.code, 0) << run.err << run.out;
  std::ifstream in(s.file("report.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  for (const char* key : {"transformation", "converged", "parameters", "sigmas", "estimator", "scale",
                          "subsets", "percent_deformed", "regions", "noise", "local_origin"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_EQ(j["params"].get<int>(), 6);  // the rigid default, determined here
  EXPECT_FALSE(j.contains("model_note"));
  ASSERT_TRUE(j.contains("stable_refinement"));
  EXPECT_GE(j["stable_refinement"]["rounds"].get<int>(), 0);
  EXPECT_FALSE(j["stable_refinement"]["stopped"].get<std::string>().empty());
  const Eigen::Matrix4d T = jsonMatrix(j["transformation"]);
  Eigen::Matrix3Xd pts(3, static_cast<Eigen::Index>(li.mate->size()));
  for (std::size_t i = 0; i < li.mate->size(); ++i)
    pts.col(static_cast<Eigen::Index>(i)) = (*li.mate)[i].getVector3fMap().cast<double>();
  EXPECT_LT(evaluation::computeTransformError(T, li.truth.matrix(), pts).max, 0.5 * 20.0);
  EXPECT_NEAR(j["percent_deformed"].get<double>(), li.percent, 3.0);
  EXPECT_FALSE(j["stable_part_ambiguous"].get<bool>());        // 20 % moved: clearly a minority
  EXPECT_NEAR(j["neighbour_noise"].get<double>(), 20.0, 4.0);  // σ = 20 (√2 σ on the patch)
  // MM (the default) compared its three fits by the stable part's scatter (≈ σ for the good ones).
  ASSERT_TRUE(j.contains("start_choice"));
  EXPECT_EQ(j["start_choice"]["stable_part_scatter"].size(), 3u);
  EXPECT_NEAR(j["start_choice"]["stable_part_scatter"]["mm"].get<double>(), 20.0, 4.0);
  EXPECT_FALSE(j["start_choice"]["chosen"].get<std::string>().empty());
  // The block start's criterion keeps 40 % of the blocks: about 40 % of the observations.
  EXPECT_GT(j["start_choice"]["block_support"].get<double>(), 0.3);
  EXPECT_LT(j["start_choice"]["block_support"].get<double>(), 0.5);
  ASSERT_GE(j["regions"].size(), 1u);
  EXPECT_EQ(j["regions"][0]["sign"].get<int>(), 1);

  pcl::PointCloud<PointResidual> res;
  ASSERT_EQ(pcl::io::loadPCDFile(s.file("res.pcd"), res), 0);
  ASSERT_EQ(res.size(), li.mate->size());
  std::size_t tp = 0, fp = 0, fn = 0;
  for (std::size_t i = 0; i < res.size(); ++i) {
    EXPECT_FLOAT_EQ(res[i].x, (*li.mate)[i].x);
    EXPECT_FLOAT_EQ(res[i].z, (*li.mate)[i].z);
    if (!std::isfinite(res[i].residual))
      continue;  // no conjugate
    const bool found = res[i].region > 0;
    tp += found && li.deformed[i];
    fp += found && !li.deformed[i];
    fn += !found && li.deformed[i];
  }
  EXPECT_GE(static_cast<double>(tp) / static_cast<double>(tp + fp), 0.95);
  EXPECT_GE(static_cast<double>(tp) / static_cast<double>(tp + fn), 0.9);
  // The file records its origin in the header too: pcl_ls3d's reader puts it in the report's frame.
  pcl::PointCloud<PointLiDAR> back;
  io::CloudInfo info;
  std::string load_error;
  ASSERT_TRUE(io::loadCloud(s.file("res.pcd"), back, info, load_error)) << load_error;
  EXPECT_TRUE(info.has_file_origin);
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(info.file_origin[k], j["local_origin"][static_cast<std::size_t>(k)].get<double>());

  // The map: a PNG and a GeoTIFF with the CRS given (deformation/test_deformation_map.cpp checks
  // their content).
  maps::Image png;
  std::string error;
  EXPECT_TRUE(maps::readPng(s.file("map.png"), png, error)) << error;
  EXPECT_GT(png.width(), 100);
  maps::Raster tif;
  std::string crs;
  ASSERT_TRUE(maps::readGeoTiff(s.file("map.tif"), tif, crs, error)) << error;
  EXPECT_TRUE(maps::sameCrs(crs, maps::crsFromUserInput("EPSG:26917")));
  EXPECT_GT(tif.validCells(), 1000u);

  // Never overwrites an input or an existing output.
  const auto clobber =
      runTool("pcl_ls3d_deformation",
              s.file("ref.pcd") + " " + s.file("epoch.pcd") + " -o " + s.file("epoch.pcd"), s.dir.string());
  EXPECT_NE(clobber.code, 0);
  EXPECT_EQ(lineCount(clobber.err), 1u) << clobber.err;
  const auto again = runTool(
      "pcl_ls3d_deformation",
      s.file("ref.pcd") + " " + s.file("epoch.pcd") + " -json " + s.file("report.json"), s.dir.string());
  EXPECT_NE(again.code, 0);
  EXPECT_NE(again.err.find("exists"), std::string::npos) << again.err;
}

TEST(DeformationTool, BadInputGivesOneErrorLine)
{
  const Scratch s;
  const pcl::PointCloud<pcl::PointXYZ> ref = smallReference(s);
  ASSERT_FALSE(ref.empty());
  pcl::PointCloud<pcl::PointXYZ> few;
  for (int i = 0; i < 4; ++i)
    few.push_back(ref[static_cast<std::size_t>(200 + i)]);
  ASSERT_EQ(pcl::io::savePCDFileBinary(s.file("few.pcd"), few), 0);
  const std::string a = s.file("ref.pcd") + " " + s.file("ref.pcd");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {s.file("ref.pcd"), "two input files"},
      {a + " -estimator ransac", "unknown -estimator"},
      {a + " -rule icp", "unknown -rule"},
      {a + " -params 5", "-params"},
      {a + " -k 0", "-k"},
      {a + " -subsets 6x", "-subsets"},
      {a + " -refine 2.5", "-refine"},
      {a + " -refine -1", "-refine"},
      {a + " -grow_k abc", "-grow_k"},
      {a + " -grow_k -1", "-grow_k"},
      {a + " -contamination 0.8", "-contamination"},
      {a + " -o " + s.file("out.las"), ".pcd, .xyz or .txt"},
      {a + " -bogus", "Unknown option"},
      {a + " -map " + s.file("m") + " -crs EPSG:99999999", "invalid -crs"},
      {s.file("missing.pcd") + " " + s.file("ref.pcd"), ""},
      {s.file("ref.pcd") + " " + s.file("few.pcd"), "failed"},
  };
  for (const auto& [args, expect] : cases) {
    const auto r = runTool("pcl_ls3d_deformation", args, s.dir.string());
    EXPECT_NE(r.code, 0) << args;
    EXPECT_EQ(lineCount(r.err), 1u) << args << ": " << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << args << ": " << r.err;
  }
  const auto help = runTool("pcl_ls3d_deformation", "-h", s.dir.string());
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.out.find("Usage"), std::string::npos);
}

// 49 % of the nodes raised in the middle, 51 % stable around them: the data alone cannot say
// which part moved (a robust estimator takes the larger one). The tool says so.
TEST(DeformationTool, NearHalfMovedIsReportedAsAmbiguous)
{
  const Scratch s;
  writeLiPair(s, 49.0, 25.0, synth::DeformationPosition::MIDDLE);
  const auto run = runTool("pcl_ls3d_deformation",
                           s.file("ref.pcd") + " " + s.file("epoch.pcd") + " -json " + s.file("report.json"),
                           s.dir.string());
  ASSERT_EQ(run.code, 0) << run.err << run.out;
  EXPECT_NE((run.out + run.err).find("only the larger"), std::string::npos) << run.out;
  std::ifstream in(s.file("report.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_GT(j["percent_deformed"].get<double>(), 40.0);
  EXPECT_TRUE(j["stable_part_ambiguous"].get<bool>());
}

// Nearly flat terrain does not determine the rigid fit: the tool says it estimated the
// translation alone, and the JSON's params and model_note say so too.
TEST(DeformationTool, FlatTerrainIsMatchedByTheTranslation)
{
  const Scratch s;
  const synth::LiSurface li = li_test::gentleTerrain();
  pcl::PointCloud<pcl::PointXYZ> ref, mate;
  pcl::copyPointCloud(*li.reference, ref);
  pcl::copyPointCloud(*li.mate, mate);
  ASSERT_EQ(pcl::io::savePCDFileBinary(s.file("ref.pcd"), ref), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinary(s.file("epoch.pcd"), mate), 0);
  const auto run = runTool("pcl_ls3d_deformation",
                           s.file("ref.pcd") + " " + s.file("epoch.pcd") + " -json " + s.file("report.json"),
                           s.dir.string());
  ASSERT_EQ(run.code, 0) << run.err << run.out;
  EXPECT_NE((run.out + run.err).find("translation only: the data do not determine the rigid fit"),
            std::string::npos)
      << run.out << run.err;
  const nlohmann::json j = readJson(s.file("report.json"));
  EXPECT_EQ(j.at("params").get<int>(), 3);
  EXPECT_NE(j.at("model_note").get<std::string>().find("translation only"), std::string::npos);
  const Eigen::Matrix4d T = jsonMatrix(j.at("transformation"));
  EXPECT_TRUE((T.topLeftCorner<3, 3>().isIdentity(1e-12))) << T;
  EXPECT_NEAR(j.at("percent_deformed").get<double>(), li.percent, 8.0);
  // Asked for the rigid fit by name, the tool gives that or refuses.
  const auto rigid = runTool("pcl_ls3d_deformation",
                             s.file("ref.pcd") + " " + s.file("epoch.pcd") + " -params 6", s.dir.string());
  EXPECT_EQ(rigid.code, 1) << rigid.out << rigid.err;
  EXPECT_NE((rigid.out + rigid.err).find("the data do not determine the move"), std::string::npos)
      << rigid.out << rigid.err;
  EXPECT_NE((rigid.out + rigid.err).find("-params 3, or no -params, estimates the translation alone"),
            std::string::npos)
      << rigid.out << rigid.err;
  // Asked for the translation, there is nothing to note.
  const auto asked =
      runTool("pcl_ls3d_deformation",
              s.file("ref.pcd") + " " + s.file("epoch.pcd") + " -params 3 -json " + s.file("asked.json"),
              s.dir.string());
  ASSERT_EQ(asked.code, 0) << asked.err << asked.out;
  const nlohmann::json a = readJson(s.file("asked.json"));
  EXPECT_EQ(a.at("params").get<int>(), 3);
  EXPECT_FALSE(a.contains("model_note"));
}

// A matching that stops at its iteration limit is not a converged answer: the outputs are
// written (marked "converged": false) and the tool says so and exits 3, where it exited 0 before
// (Toronto's all-point pair ended MAX_ITERATIONS with exit 0). With the default limit the same
// pair converges and exits 0.
TEST(DeformationTool, IterationLimitExitsThreeWithOutputsMarked)
{
  const Scratch s;
  writeLiPair(s, 9.0, 10.0, synth::DeformationPosition::UPPER_LEFT);
  const std::string inputs = s.file("ref.pcd") + " " + s.file("epoch.pcd");
  const auto limited =
      runTool("pcl_ls3d_deformation",
              inputs + " -max_iter 1 -json " + s.file("limited.json") + " -o " + s.file("limited.pcd"),
              s.dir.string());
  EXPECT_EQ(limited.code, 3) << limited.err << limited.out;
  EXPECT_NE((limited.out + limited.err).find("not CONVERGED"), std::string::npos) << limited.out;
  EXPECT_TRUE(fs::exists(s.file("limited.pcd")));
  {
    std::ifstream in(s.file("limited.json"));
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_FALSE(j["converged"].get<bool>());
    EXPECT_EQ(j["termination"].get<std::string>(), "MAX_ITERATIONS");
  }
  const auto full = runTool("pcl_ls3d_deformation", inputs + " -json " + s.file("full.json"), s.dir.string());
  EXPECT_EQ(full.code, 0) << full.err << full.out;
  EXPECT_NE(runTool("pcl_ls3d_deformation", inputs + " -max_iter 0", s.dir.string()).code, 0);
}

// Outputs that cannot be made end with one error line and exit 1, not an abort: a residual
// cloud under /proc (PCL threw pcl::IOException) and a map cell giving 1e15 cells (bad_alloc).
TEST(DeformationTool, UnwritableOutputsFailWithOneLine)
{
  const Scratch s;
  writeLiPair(s, 9.0, 10.0, synth::DeformationPosition::UPPER_LEFT);
  const std::string inputs = s.file("ref.pcd") + " " + s.file("epoch.pcd");
  auto r = runTool("pcl_ls3d_deformation", inputs + " -o /proc/pcl_ls3d_residuals.pcd", s.dir.string());
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  r = runTool("pcl_ls3d_deformation", inputs + " -map " + s.file("m") + " -map_cell 1e-4", s.dir.string());
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("raise -map_cell"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(s.file("m.png")));
}

namespace {
/// The tool on the pair writeLiPairAtUtm() wrote, with a JSON report (report.json).
auto
analyseUtmPair(const Scratch& s)
{
  return runTool("pcl_ls3d_deformation",
                 s.file("ref.xyz") + " " + s.file("epoch.xyz") + " -json " + s.file("report.json"),
                 s.dir.string());
}

}  // namespace

// The 4x4 matrix printed on the console acts on input coordinates; at UTM-like coordinates
// (5e6 m) 8 decimals in the rotation put the points 1-2 cm off. Applied to the data, the printed
// matrix must give what the JSON's full-precision matrix gives, to well under a millimetre.
TEST(DeformationTool, PrintedMatrixReproducesTheJsonAtProjectedCoordinates)
{
  const Scratch s;
  const std::vector<Eigen::Vector3d> epoch = writeLiPairAtUtm(s);
  const auto run = analyseUtmPair(s);
  ASSERT_EQ(run.code, 0) << run.err << run.out;
  std::istringstream out(run.out);
  std::string line;
  while (std::getline(out, line) && line.find("Transformation (EPOCH -> REFERENCE") == std::string::npos) {
  }
  Eigen::Matrix4d printed;
  for (int r = 0; r < 4; ++r) {
    ASSERT_TRUE(std::getline(out, line)) << run.out;
    std::istringstream row(line);
    for (int c = 0; c < 4; ++c)
      ASSERT_TRUE(row >> printed(r, c)) << line;
  }
  std::ifstream in(s.file("report.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  const Eigen::Matrix4d T = jsonMatrix(j["transformation"]);
  EXPECT_GT(T.col(3).head<3>().norm(), 1e4);  // the rotation acts about the far coordinate origin
  EXPECT_LT(largestDifference(printed, T, epoch), 1e-4);
}

// The JSON's parameters are in a reduced frame; the note names the origins and the JSON holds
// them, so a reader rebuilds the transformation from them: x_t = o_t + t + m R (x_s - o_s) with
// R = R_Y(phi) R_X(omega) R_Z(kappa) (similarity_transform.h), equal to the JSON's matrix. The
// console says which frame and prints both origins.
TEST(DeformationTool, JsonParametersRebuildTheTransformation)
{
  const Scratch s;
  const std::vector<Eigen::Vector3d> epoch = writeLiPairAtUtm(s);
  const auto run = analyseUtmPair(s);
  ASSERT_EQ(run.code, 0) << run.err << run.out;
  std::ifstream in(s.file("report.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  const std::string note = j["parameters_note"].get<std::string>();
  for (const char* key : {"local_origin_source", "local_origin_target"}) {
    EXPECT_NE(note.find(key), std::string::npos) << note;
    ASSERT_TRUE(j.contains(key)) << key;
  }
  const Eigen::Vector3d o_s = jsonVector(j["local_origin_source"]),
                        o_t = jsonVector(j["local_origin_target"]);
  const nlohmann::json& p = j["parameters"];
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(p["phi"].get<double>(), Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(p["omega"].get<double>(), Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(p["kappa"].get<double>(), Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  const Eigen::Vector3d t(p["tx"].get<double>(), p["ty"].get<double>(), p["tz"].get<double>());
  Eigen::Matrix4d rebuilt = Eigen::Matrix4d::Identity();
  rebuilt.topLeftCorner<3, 3>() = p["m"].get<double>() * R;
  rebuilt.topRightCorner<3, 1>() = o_t + t - rebuilt.topLeftCorner<3, 3>() * o_s;
  EXPECT_LT(largestDifference(rebuilt, jsonMatrix(j["transformation"]), epoch), 1e-6);
  char origins[160];
  std::snprintf(origins, sizeof(origins), "o_s (%.4f, %.4f, %.4f), o_t (%.4f, %.4f, %.4f)", o_s.x(), o_s.y(),
                o_s.z(), o_t.x(), o_t.y(), o_t.z());
  EXPECT_NE(run.out.find(origins), std::string::npos) << origins << "\n" << run.out;
}

// Two identical inputs: every residual is 0 and the parameters' sigma cannot be estimated. The
// console says so in pcl_ls3d_register's words instead of printing "(nan)".
TEST(DeformationTool, IdenticalInputsSayExactFit)
{
  const Scratch s;
  writeLiPair(s, 20.0, 10.0, synth::DeformationPosition::LOWER_RIGHT);
  const auto run = runTool("pcl_ls3d_deformation",
                           s.file("ref.pcd") + " " + s.file("ref.pcd") + " -json " + s.file("report.json"),
                           s.dir.string());
  ASSERT_EQ(run.code, 0) << run.err << run.out;
  EXPECT_EQ(run.out.find("nan"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("sigma not estimable (exact fit)"), std::string::npos) << run.out;
  std::ifstream in(s.file("report.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_TRUE(j["sigmas"]["tx"].is_null());
}

// -h tells what a run prints: MM draws 500 FAST-LTS starts per search round, so a default run
// reports 500 x its rounds (at most 3) subsets.
TEST(DeformationTool, HelpStatesTheSubsetsARunDraws)
{
  const Scratch s;
  writeLiPair(s, 20.0, 10.0, synth::DeformationPosition::LOWER_RIGHT);
  const auto run =
      runTool("pcl_ls3d_deformation", s.file("ref.pcd") + " " + s.file("epoch.pcd"), s.dir.string());
  ASSERT_EQ(run.code, 0) << run.err << run.out;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(run.out, m, std::regex("(\\d+) subsets in (\\d+) round")));
  const int drawn = std::stoi(m[1]), rounds = std::stoi(m[2]);
  EXPECT_EQ(drawn, 500 * rounds);
  EXPECT_LE(rounds, 3);
  const auto help = runTool("pcl_ls3d_deformation", "-h", s.dir.string());
  EXPECT_NE(help.out.find("per search round"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("mm 500 FAST-LTS"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("up to 3 rounds"), std::string::npos) << help.out;
}

// Options that contradict each other are refused before any work, with one error line naming
// the options as typed; -params gives the same range whatever was wrong.
TEST(DeformationTool, ConflictingOptionsAreRefused)
{
  const Scratch s;
  const pcl::PointCloud<pcl::PointXYZ> ref = smallReference(s);
  ASSERT_FALSE(ref.empty());
  const std::string a = s.file("ref.pcd") + " " + s.file("ref.pcd") + " -json " + s.file("r.json");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {a + " -grow_k 4", "-grow_k 4 must be below -k (3)"},
      {a + " -k 2 -grow_k 2.5", "-grow_k 2.5 must be below -k (2)"},
      {a + " -k 2 -grow_k 2", "must be below -k"},
      {a + " -lod95 -k 3", "-k and -lod95 exclude each other"},
      {a + " -lod95 -grow_k 2", "-grow_k 2 must be below -lod95's threshold (1.96)"},
      {a + " -params 6x", "-params expects 6, 7 or 3, got '6x'"},
      {a + " -params 5", "-params expects 6, 7 or 3, got '5'"},
      {a + " -params 1", "-params expects 6, 7 or 3, got '1'"},
      {a + " -max_iter 0", "-max_iter"},
  };
  for (const auto& [args, expect] : cases) {
    const auto r = runTool("pcl_ls3d_deformation", args, s.dir.string());
    EXPECT_EQ(r.code, 1) << args;
    EXPECT_EQ(lineCount(r.err), 1u) << args << ": " << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(r.err.find("max_iterations"), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(s.file("r.json"))) << args;  // refused before any work
  }
  // Below -k, or off, hysteresis is accepted.
  for (const char* ok : {" -k 2 -grow_k 1.5", " -grow_k 0", " -lod95", " -lod95 -grow_k 1.3"}) {
    const auto r =
        runTool("pcl_ls3d_deformation", s.file("ref.pcd") + " " + s.file("ref.pcd") + ok, s.dir.string());
    EXPECT_EQ(r.code, 0) << ok << ": " << r.err;
    // -lod95 with the default -grow_k 2 (above its 1.96): runs, and says the regions do not grow.
    EXPECT_EQ(r.err.find("do not grow") != std::string::npos, std::string(ok) == " -lod95")
        << ok << ": " << r.err;
  }
}

// The console summary holds the whole estimator description and its tail (the subsets), however
// long the description grows.
TEST(DeformationTool, ConsoleSummaryIsNotCut)
{
  RobustMatchingReport r;
  r.estimator = std::string(300, 'e');
  r.termination = TerminationType::CONVERGED;
  r.iterations = 312;
  r.subsets_drawn = 1500;
  r.rounds = 3;
  const std::string line = r.brief();
  EXPECT_EQ(line.substr(0, 300), r.estimator);
  EXPECT_NE(line.find("312 iterations, 1500 subsets in 3 round(s)"), std::string::npos) << line;
}

// A reference on one line has no surface: whatever the estimator, one error line names it as
// degenerate (not "no overlap") and the exit is 1 as for any failed matching (-h, ARCHITECTURE).
TEST(DeformationTool, DegenerateReferenceIsNamed)
{
  const Scratch s;
  pcl::PointCloud<pcl::PointXYZ> line, strip;
  for (int i = 0; i <= 400; ++i)
    line.push_back(pcl::PointXYZ(0.05f * static_cast<float>(i), 0.f, 0.f));
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j)
      strip.push_back(pcl::PointXYZ(0.5f * static_cast<float>(i), 0.05f * static_cast<float>(j) - 1.f, 0.f));
  ASSERT_EQ(pcl::io::savePCDFileBinary(s.file("line.pcd"), line), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinary(s.file("strip.pcd"), strip), 0);
  for (const char* estimator : {"mm", "lms", "md"}) {
    const auto r =
        runTool("pcl_ls3d_deformation",
                s.file("line.pcd") + " " + s.file("strip.pcd") + " -estimator " + estimator, s.dir.string());
    EXPECT_EQ(r.code, 1) << estimator << ": " << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << estimator << ": " << r.err;
    EXPECT_NE(r.err.find("degenerate: its points there are collinear"), std::string::npos)
        << estimator << ": " << r.err;
    EXPECT_EQ(r.err.find("no overlap"), std::string::npos) << estimator << ": " << r.err;
  }
}
