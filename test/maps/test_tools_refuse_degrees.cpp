// Every tool that measures distances refuses inputs in degrees (or earth-centred) in one line,
// before any work, whether a LAS or a PCD header declares the CRS. Before, pcl_ls3d_register
// matched a generated pair written in EPSG:4326 (x, y in degrees, z in metres) to a 74 m
// "shift" and reported it CONVERGED and trustworthy. And the PCDs the tools write record the
// inputs' CRS, and inputs declaring different CRSs are warned of.
#include "io/io_test_utils.h"
#include "io/tool_json.h"
#include "io/tool_run.h"

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/point_types.h>
#include <pcl_ls3d/synth/registration_pair.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using pcl_ls3d_test::jsonMatrix;
using pcl_ls3d_test::readJson;
using pcl_ls3d_test::runTool;
using pcl_ls3d_test::TempDir;

namespace {

/// A wavy 30 x 30 patch of 1 m spacing, x and y divided by \a per_unit (degrees: 1e5 m).
void
writePatch(const std::string& path, const std::string& crs, double per_unit, float dz)
{
  pcl::PointCloud<pcl_ls3d::PointLiDAR> c;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j)
      c.push_back(pcl_ls3d::PointLiDAR(static_cast<float>(i / per_unit), static_cast<float>(j / per_unit),
                                       std::sin(0.3f * i) + std::cos(0.2f * j) + dz));
  pcl_ls3d::io::SaveOptions o;
  pcl_ls3d::maps::recordCrs(pcl_ls3d::maps::crsFromUserInput(crs), o);  // "": none
  o.las_scale = {0.001 / per_unit, 0.001 / per_unit, 0.001};
  std::string error;
  ASSERT_TRUE(pcl_ls3d::io::saveCloud(path, c, Eigen::Vector3d(2.0, 48.0, 0.0), error, o)) << error;
}

}  // namespace

TEST(ToolsRefuseDegrees, OneLineBeforeAnyWork)
{
  const TempDir dir("ls3d_degrees");
  const std::string a = dir.file("a.las"), b = dir.file("b.las");
  writePatch(a, "EPSG:4326", 1e5, 0.0f);
  writePatch(b, "EPSG:4326", 1e5, 0.2f);
  const std::string pair = a + " " + b;
  const std::string calls[][2] = {
      {"pcl_ls3d_register", pair + " -o " + dir.file("aligned.las")},
      {"pcl_ls3d_compare", pair},
      {"pcl_ls3d_deformation", pair + " -o " + dir.file("residuals.pcd")},
      {"pcl_ls3d_strip_adjust", pair + " -o " + dir.file("out")},
      {"pcl_ls3d_segment", a + " -o " + dir.file("seg.pcd")},
  };
  for (const auto& call : calls) {
    SCOPED_TRACE(call[0]);
    const pcl_ls3d_test::ToolRun r = runTool(call[0], call[1], dir.path.string());
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("is in degrees (WGS 84)"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // one line
  }
  EXPECT_FALSE(fs::exists(dir.file("aligned.las")));
  EXPECT_FALSE(fs::exists(dir.file("seg.pcd")));
  EXPECT_FALSE(fs::exists(dir.file("residuals.pcd")));
  // Converted to PCD, the files keep their CRS in the header and are refused the same way.
  ASSERT_EQ(runTool("pcl_ls3d_convert", a + " " + dir.file("a.pcd"), dir.path.string()).code, 0);
  ASSERT_EQ(runTool("pcl_ls3d_convert", b + " " + dir.file("b.pcd"), dir.path.string()).code, 0);
  const pcl_ls3d_test::ToolRun pcd =
      runTool("pcl_ls3d_register", dir.file("a.pcd") + " " + dir.file("b.pcd"), dir.path.string());
  EXPECT_EQ(pcd.code, 1);
  EXPECT_NE(pcd.err.find("is in degrees (WGS 84)"), std::string::npos) << pcd.err;
  // Earth-centred coordinates too; a projected CRS is read on.
  const std::string ecef = dir.file("ecef.las"), c = dir.file("c.las"), d = dir.file("d.las");
  writePatch(ecef, "EPSG:4978", 1.0, 0.2f);
  EXPECT_NE(runTool("pcl_ls3d_register", a + " " + ecef, dir.path.string())
                .err.find("'" + ecef + "' is in earth-centred"),
            std::string::npos);
  writePatch(c, "EPSG:2154", 1.0, 0.0f);
  writePatch(d, "EPSG:2154", 1.0, 0.2f);
  EXPECT_EQ(runTool("pcl_ls3d_register", c + " " + d, dir.path.string()).err.find("degrees"),
            std::string::npos);
}

// Clouds the tools write as PCD from projected inputs record the CRS in their header, so that
// the next tool (or pcl_ls3d_convert back to LAS) knows it.
TEST(ToolsKeepTheCrs, PcdOutputsRecordTheInputsCrs)
{
  const TempDir dir("ls3d_keep_crs");
  const std::string c = dir.file("c.las"), d = dir.file("d.las");
  writePatch(c, "EPSG:2154", 1.0, 0.0f);
  writePatch(d, "EPSG:2154", 1.0, 0.2f);
  ASSERT_EQ(
      runTool("pcl_ls3d_register", d + " " + c + " -o " + dir.file("aligned.pcd"), dir.path.string()).code,
      0);
  const pcl_ls3d_test::ToolRun def =
      runTool("pcl_ls3d_deformation", c + " " + d + " -o " + dir.file("residuals.pcd"), dir.path.string());
  ASSERT_TRUE(def.code == 0 || def.code == 3) << def.err;
  // The strip adjustment's corrected strips, from PCD strips that record the CRS.
  for (const std::string& s : {c, d})
    ASSERT_EQ(
        runTool("pcl_ls3d_convert", s + " " + s.substr(0, s.size() - 3) + "pcd", dir.path.string()).code, 0);
  const pcl_ls3d_test::ToolRun strips =
      runTool("pcl_ls3d_strip_adjust", dir.file("c.pcd") + " " + dir.file("d.pcd") + " -o " + dir.file("out"),
              dir.path.string());
  ASSERT_EQ(strips.code, 0) << strips.err;
  const std::string lambert = pcl_ls3d::maps::crsFromUserInput("EPSG:2154");
  for (const char* name : {"aligned.pcd", "residuals.pcd", "out/c.pcd", "out/d.pcd"}) {
    SCOPED_TRACE(name);
    pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
    pcl_ls3d::io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(pcl_ls3d::io::loadCloud(dir.file(name), cloud, info, error)) << error;
    EXPECT_TRUE(pcl_ls3d::maps::sameCrs(info.file_crs_wkt, lambert)) << info.file_crs_wkt;
  }
}

// Inputs declaring different horizontal CRSs are matched as they are, with a warning that says
// so; the same projection with and without a vertical part is no difference.
TEST(ToolsWarnOfDifferentCrs, OneWarningNotARefusal)
{
  const TempDir dir("ls3d_crs_mismatch");
  const std::string lambert = dir.file("lambert.las"), with_height = dir.file("height.las"),
                    utm = dir.file("utm.las"), none = dir.file("none.las");
  writePatch(none, "", 1.0, 0.1f);
  writePatch(lambert, "EPSG:2154", 1.0, 0.0f);
  writePatch(with_height, "EPSG:2154+5720", 1.0, 0.2f);  // + NGF-IGN69 height
  writePatch(utm, "EPSG:32631", 1.0, 0.2f);
  const pcl_ls3d_test::ToolRun same =
      runTool("pcl_ls3d_register", with_height + " " + lambert, dir.path.string());
  EXPECT_EQ(same.code, 0) << same.err;
  EXPECT_EQ(same.err.find("declares"), std::string::npos) << same.err;
  // The CRS read from a PCD header too; the strips' note names the first input that declares
  // one, not the first input.
  ASSERT_EQ(runTool("pcl_ls3d_convert", utm + " " + dir.file("utm.pcd"), dir.path.string()).code, 0);
  const std::string calls[][2] = {
      {"pcl_ls3d_register", utm + " " + lambert},
      {"pcl_ls3d_compare", utm + " " + lambert + " -methods ls3d-lnd"},
      {"pcl_ls3d_deformation", lambert + " " + utm},
      {"pcl_ls3d_strip_adjust", none + " " + lambert + " " + utm + " -o " + dir.file("out")},
  };
  for (const auto& call : calls) {
    SCOPED_TRACE(call[0]);
    const pcl_ls3d_test::ToolRun r = runTool(call[0], call[1], dir.path.string());
    EXPECT_NE(r.code, 1) << r.err;
    EXPECT_NE(
        (r.out + r.err)
            .find("'" + utm + "' declares WGS 84 / UTM zone 31N, '" + lambert + "' RGF93 v1 / Lambert-93"),
        std::string::npos)
        << r.out << r.err;
  }
  const pcl_ls3d_test::ToolRun pcd =
      runTool("pcl_ls3d_register", dir.file("utm.pcd") + " " + lambert, dir.path.string());
  EXPECT_NE(pcd.err.find("utm.pcd' declares WGS 84 / UTM zone 31N"), std::string::npos) << pcd.err;
}

// A compound CRS whose heights are in another unit than its plan coordinates (NAD83 / Oregon
// LCC in metres + NAVD88 height in US feet, as PDAL's autzen-bmx files) is said so: the tools
// convert the heights to the plan unit, in one line each (the strip adjustment: a note). One
// unit throughout: nothing said.
TEST(ToolsSayHeightsAreConverted, HeightsInFeetOverMetres)
{
  const std::string mixed_crs = pcl_ls3d::maps::crsFromUserInput("EPSG:32631+6360");
  ASSERT_FALSE(mixed_crs.empty());
  ASSERT_NEAR(pcl_ls3d::maps::crsVerticalUnit(mixed_crs), 0.3048006, 1e-6);
  EXPECT_TRUE(pcl_ls3d::maps::crsMixesUnits(mixed_crs));
  EXPECT_NEAR(pcl_ls3d::maps::planUnitsPerHeightUnit(mixed_crs), 0.3048006, 1e-6);
  const std::string metres = pcl_ls3d::maps::crsFromUserInput("EPSG:2154+5720");
  EXPECT_FALSE(pcl_ls3d::maps::crsMixesUnits(metres));
  EXPECT_EQ(pcl_ls3d::maps::planUnitsPerHeightUnit(metres), 1.0);
  const TempDir dir("ls3d_mixed_units");
  const std::string a = dir.file("a.las"), b = dir.file("b.las");
  writePatch(a, "EPSG:32631+6360", 1.0, 0.0f);
  writePatch(b, "EPSG:32631+6360", 1.0, 0.2f);
  const std::string said = "'" + a + "' declares heights in ft and plan coordinates in m";
  const std::string calls[][3] = {
      {"pcl_ls3d_register", b + " " + a, "heights are converted to m (x 0.3048006)"},
      {"pcl_ls3d_compare", b + " " + a + " -methods ls3d-lnd", "heights are converted to m"},
      {"pcl_ls3d_deformation", a + " " + b, "heights are converted to m"},
      {"pcl_ls3d_strip_adjust", a + " " + b + " -o " + dir.file("out"), "heights are converted to m"},
  };
  for (const auto& call : calls) {
    SCOPED_TRACE(call[0]);
    const pcl_ls3d_test::ToolRun r = runTool(call[0], call[1], dir.path.string());
    EXPECT_NE(r.code, 1) << r.err;
    const std::string text = r.out + r.err;
    EXPECT_NE(text.find(said + " (WGS 84 / UTM zone 31N + NAVD88 height (ftUS)): " + call[2]),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find("mix the two units"), std::string::npos) << text;
  }
  // pcl_ls3d_info names the CRS and says what the tools do with such heights; not for one unit.
  const pcl_ls3d_test::ToolRun info = runTool("pcl_ls3d_info", a, dir.path.string());
  EXPECT_NE(info.out.find("crs WGS 84 / UTM zone 31N + NAVD88 height (ftUS) (declared in the LAS "
                          "VLRs)\n  heights in ft, plan coordinates in m (x 0.3048006)"),
            std::string::npos)
      << info.out;
  const std::string c = dir.file("c.las");
  writePatch(c, "EPSG:2154+5720", 1.0, 0.0f);
  const pcl_ls3d_test::ToolRun one_unit = runTool("pcl_ls3d_info", c, dir.path.string());
  EXPECT_NE(one_unit.out.find("crs RGF93 v1 / Lambert-93 + NGF-IGN69 height"), std::string::npos)
      << one_unit.out;
  EXPECT_EQ(one_unit.out.find("heights in"), std::string::npos) << one_unit.out;
}

namespace {

/// Metres per US survey foot.
constexpr double kUsFoot = 1200.0 / 3937.0;

/// diag(1, 1, factor, 1): heights times factor.
Eigen::Matrix4d
heightScale(double factor)
{
  Eigen::Matrix4d S = Eigen::Matrix4d::Identity();
  S(2, 2) = factor;
  return S;
}

/// A cloud written with heights in units of \a metres_per_height_unit, declaring \a crs (none
/// when empty).
void
writeWithHeights(const std::string& path, pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud,
                 const Eigen::Vector3d& origin, double metres_per_height_unit, const std::string& crs)
{
  ASSERT_FALSE(cloud.empty());
  for (auto& p : cloud)
    p.z = static_cast<float>(p.z / metres_per_height_unit);
  pcl_ls3d::io::SaveOptions o;
  if (!crs.empty())
    pcl_ls3d::maps::recordCrs(pcl_ls3d::maps::crsFromUserInput(crs), o);
  o.las_scale = {0.001, 0.001, 0.001};
  std::string error;
  ASSERT_TRUE(pcl_ls3d::io::saveCloud(
      path, cloud, heightScale(1.0 / metres_per_height_unit).block<3, 3>(0, 0) * origin, error, o))
      << error;
}

/// A cloud written as LAS declaring UTM 31N (m) + NAVD88 height (ftUS), heights in feet.
void
writeInFeet(const std::string& path, const pcl::PointCloud<pcl_ls3d::PointLiDAR>& cloud,
            const Eigen::Vector3d& origin)
{
  writeWithHeights(path, cloud, origin, kUsFoot, "EPSG:32631+6360");
}

/// The source's points in its file's coordinates (heights in US feet).
std::vector<Eigen::Vector4d>
sourceInFeet(const pcl::PointCloud<pcl_ls3d::PointLiDAR>& source, const Eigen::Vector3d& origin)
{
  std::vector<Eigen::Vector4d> out;
  for (const auto& p : source)
    out.push_back(heightScale(1.0 / kUsFoot) * (p.getVector3fMap().cast<double>() + origin).homogeneous());
  return out;
}

/// Mean distance in metres between where T and the truth put the source's points (the source
/// file's coordinates, heights in US feet, into the target file's, heights in units of
/// \a target_unit metres).
double
meanErrorInMetres(const Eigen::Matrix4d& T, const Eigen::Matrix4d& truth,
                  const std::vector<Eigen::Vector4d>& source, double target_unit)
{
  double sum = 0.0;
  for (const Eigen::Vector4d& x : source)
    sum += (heightScale(target_unit) * (T * x - truth * x)).norm();
  return sum / static_cast<double>(source.size());
}

/// Mean height distance in metres between a written cloud (heights in units of \a unit metres)
/// and where \a expected puts the source's points in that file's coordinates.
double
meanHeightErrorInMetres(const std::string& path, const Eigen::Matrix4d& expected,
                        const std::vector<Eigen::Vector4d>& source, double unit)
{
  pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
  pcl_ls3d::io::CloudInfo info;
  std::string error;
  EXPECT_TRUE(pcl_ls3d::io::loadCloud(path, cloud, info, error)) << error;
  EXPECT_EQ(cloud.size(), source.size());
  if (cloud.size() != source.size())
    return std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    sum += std::abs(cloud[i].z + info.origin.z() - (expected * source[i]).z()) * unit;
  return sum / static_cast<double>(cloud.size());
}

}  // namespace

// The same compound CRS on a generated pair tilted by 1.1 degrees: register, compare and
// deformation match with heights in metres and give the transformation back in the files'
// coordinates: the source in feet onto a target in feet, in metres (EPSG:32631+5703), or in feet
// without a CRS (taken in the source's units). The pair in metres is matched to 0.03 m
// (register's position sigma 0.02 m); before, the feet pair came out 0.5 m off, CONVERGED and
// trustworthy.
TEST(ToolsWorkInThePlanUnit, HeightsInFeetOverMetres)
{
  pcl_ls3d::synth::RegistrationPairSettings settings;
  settings.size_x = settings.size_y = 120.0;
  settings.truth.t = Eigen::Vector3d(0.5, -0.3, 0.2);
  settings.truth.phi = 0.02;
  settings.truth.omega = -0.015;
  settings.truth.kappa = 0.03;
  settings.origin = Eigen::Vector3d(500000.0, 5000000.0, 100.0);
  const pcl_ls3d::synth::RegistrationPair pair = pcl_ls3d::synth::makeRegistrationPair(settings);
  const TempDir dir("ls3d_plan_unit");
  const std::string source = dir.file("source.las");
  writeInFeet(source, *pair.source, pair.origin);
  const std::vector<Eigen::Vector4d> source_ft = sourceInFeet(*pair.source, pair.origin);
  struct TargetCase
  {
    const char* file;
    double unit;      ///< metres per height unit
    const char* crs;  ///< "": none
  };
  for (const TargetCase& c :
       {TargetCase{"target.las", kUsFoot, "EPSG:32631+6360"},
        TargetCase{"target_m.las", 1.0, "EPSG:32631+5703"}, TargetCase{"target_nocrs.pcd", kUsFoot, ""}}) {
    SCOPED_TRACE(c.file);
    const std::string target = dir.file(c.file), stem = fs::path(c.file).stem().string();
    writeWithHeights(target, *pair.target, pair.origin, c.unit, c.crs);
    // The truth in the files' coordinates: source feet to metres, the true move, metres to the
    // target's unit.
    const Eigen::Matrix4d truth = heightScale(1.0 / c.unit) * pair.globalTruthMatrix() * heightScale(kUsFoot);
    nlohmann::json truth_json;
    for (int r = 0; r < 4; ++r)
      truth_json["transformation"].push_back({truth(r, 0), truth(r, 1), truth(r, 2), truth(r, 3)});
    std::ofstream(dir.file(stem + "_truth.json")) << truth_json.dump();

    const pcl_ls3d_test::ToolRun reg =
        runTool("pcl_ls3d_register",
                source + " " + target + " -json " + dir.file(stem + "_reg.json") + " -o " +
                    dir.file(stem + "_aligned.pcd"),
                dir.path.string());
    ASSERT_EQ(reg.code, 0) << reg.err;
    EXPECT_EQ((reg.out + reg.err).find("mix the two units"), std::string::npos);
    EXPECT_EQ(std::string(c.crs).empty(),
              (reg.out + reg.err).find("target_nocrs.pcd' declares no CRS, taken as heights in ft") !=
                  std::string::npos)
        << reg.out;
    const nlohmann::json reg_json = readJson(dir.file(stem + "_reg.json"));
    EXPECT_LT(meanErrorInMetres(jsonMatrix(reg_json.at("transformation")), truth, source_ft, c.unit), 0.06);
    EXPECT_NEAR(reg_json.at("heights").at("plan_units_per_height_unit").at("source").get<double>(), kUsFoot,
                1e-9);
    // The aligned source in the target's frame and height unit where the truth puts it.
    EXPECT_LT(meanHeightErrorInMetres(dir.file(stem + "_aligned.pcd"), truth, source_ft, c.unit), 0.02);

    const pcl_ls3d_test::ToolRun cmp =
        runTool("pcl_ls3d_compare",
                source + " " + target + " -methods ls3d-lnd -truth " + dir.file(stem + "_truth.json") +
                    " -json " + dir.file(stem + "_cmp.json"),
                dir.path.string());
    ASSERT_EQ(cmp.code, 0) << cmp.err;
    const nlohmann::json row = readJson(dir.file(stem + "_cmp.json")).at("methods").at(0);
    // compare's own error (metres: working coordinates) and the one of its transformation in the
    // files' coordinates agree.
    const double compare_error = row.at("error").at("mean").get<double>();
    EXPECT_LT(compare_error, 0.06);
    EXPECT_NEAR(meanErrorInMetres(jsonMatrix(row.at("transformation")), truth, source_ft, c.unit),
                compare_error, 1e-4);

    const pcl_ls3d_test::ToolRun def =
        runTool("pcl_ls3d_deformation", target + " " + source + " -json " + dir.file(stem + "_def.json"),
                dir.path.string());
    ASSERT_EQ(def.code, 0) << def.err;
    EXPECT_LT(meanErrorInMetres(jsonMatrix(readJson(dir.file(stem + "_def.json")).at("transformation")),
                                truth, source_ft, c.unit),
              0.06);
  }
  // A LAS source moved to LAS keeps its header and CRS, so its heights stay in feet, on a target
  // in metres as well.
  ASSERT_EQ(runTool("pcl_ls3d_register",
                    source + " " + dir.file("target_m.las") + " -o " + dir.file("aligned_m.las"),
                    dir.path.string())
                .code,
            0);
  const Eigen::Matrix4d truth_in_feet =
      heightScale(1.0 / kUsFoot) * pair.globalTruthMatrix() * heightScale(kUsFoot);
  EXPECT_LT(meanHeightErrorInMetres(dir.file("aligned_m.las"), truth_in_feet, source_ft, kUsFoot), 0.02);
}

namespace {

/// The largest plan and height (metres) distances between the same points of a cloud in metres
/// and one with heights in US feet.
std::pair<double, double>
largestDifference(const std::string& metres, const std::string& feet)
{
  pcl::PointCloud<pcl_ls3d::PointLiDAR> m, ft;
  pcl_ls3d::io::CloudInfo im, ift;
  std::string error;
  EXPECT_TRUE(pcl_ls3d::io::loadCloud(metres, m, im, error)) << error;
  EXPECT_TRUE(pcl_ls3d::io::loadCloud(feet, ft, ift, error)) << error;
  EXPECT_EQ(m.size(), ft.size());
  double plan = 0.0, height = 0.0;
  for (std::size_t i = 0; i < std::min(m.size(), ft.size()); ++i) {
    const Eigen::Vector3d a = m[i].getVector3fMap().cast<double>() + im.origin,
                          b = ft[i].getVector3fMap().cast<double>() + ift.origin;
    plan = std::max(plan, (a - b).head<2>().norm());
    height = std::max(height, std::abs(a.z() - b.z() * kUsFoot));
  }
  return {plan, height};
}

}  // namespace

// The strip adjustment of generated strips with heights in feet corrects them as the same
// strips in metres, to the LAS files' millimetre (the corrections move the strips by up to
// 0.5 m); the corrected strips keep their heights in feet.
TEST(ToolsWorkInThePlanUnit, StripsInFeetOverMetres)
{
  const TempDir dir("ls3d_strips_plan_unit");
  ASSERT_EQ(runTool("pcl_ls3d_synth",
                    "strips -o " + dir.file("m") + " -split -format las -strips 3 -length 200 -swath 100",
                    dir.path.string())
                .code,
            0);
  std::string metres, feet;
  for (const char* name : {"strip_1.las", "strip_2.las", "strip_3.las"}) {
    pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
    pcl_ls3d::io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(pcl_ls3d::io::loadCloud(dir.file(std::string("m/") + name), cloud, info, error));
    writeInFeet(dir.file(std::string("ft_") + name), cloud, info.origin);
    metres += " " + dir.file(std::string("m/") + name);
    feet += " " + dir.file(std::string("ft_") + name);
  }
  ASSERT_EQ(runTool("pcl_ls3d_strip_adjust", metres + " -o " + dir.file("out_m"), dir.path.string()).code, 0);
  ASSERT_EQ(runTool("pcl_ls3d_strip_adjust", feet + " -o " + dir.file("out_ft"), dir.path.string()).code, 0);
  for (const char* name : {"strip_1.las", "strip_3.las"}) {
    SCOPED_TRACE(name);
    const auto [plan_moved, height_moved] =
        largestDifference(dir.file(std::string("m/") + name), dir.file(std::string("out_ft/ft_") + name));
    EXPECT_GT(std::max(plan_moved, height_moved), 0.1);  // corrected: not the input
    const auto [plan, height] =
        largestDifference(dir.file(std::string("out_m/") + name), dir.file(std::string("out_ft/ft_") + name));
    EXPECT_LT(plan, 0.005);
    EXPECT_LT(height, 0.003);
  }
}
