// Every tool that measures distances refuses inputs in degrees (or earth-centred) in one line,
// before any work, whether a LAS or a PCD header declares the CRS. Before, pcl_ls3d_register
// matched a generated pair written in EPSG:4326 (x, y in degrees, z in metres) to a 74 m
// "shift" and reported it CONVERGED and trustworthy. And the PCDs the tools write record the
// inputs' CRS, and inputs declaring different CRSs are warned of.
#include "io/io_test_utils.h"
#include "io/tool_run.h"

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/point_types.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;
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
      c.push_back(pcl_ls3d::PointLiDAR(static_cast<float>(i / per_unit),
                                       static_cast<float>(j / per_unit),
                                       std::sin(0.3f * i) + std::cos(0.2f * j) + dz));
  pcl_ls3d::io::SaveOptions o;
  pcl_ls3d::maps::recordCrs(pcl_ls3d::maps::crsFromUserInput(crs), o);  // "": none
  o.las_scale = {0.001 / per_unit, 0.001 / per_unit, 0.001};
  std::string error;
  ASSERT_TRUE(pcl_ls3d::io::saveCloud(path, c, Eigen::Vector3d(2.0, 48.0, 0.0), error, o))
      << error;
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
  const pcl_ls3d_test::ToolRun pcd = runTool(
      "pcl_ls3d_register", dir.file("a.pcd") + " " + dir.file("b.pcd"), dir.path.string());
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
  ASSERT_EQ(runTool("pcl_ls3d_register", d + " " + c + " -o " + dir.file("aligned.pcd"),
                    dir.path.string()).code, 0);
  const pcl_ls3d_test::ToolRun def = runTool(
      "pcl_ls3d_deformation", c + " " + d + " -o " + dir.file("residuals.pcd"), dir.path.string());
  ASSERT_TRUE(def.code == 0 || def.code == 3) << def.err;
  // The strip adjustment's corrected strips, from PCD strips that record the CRS.
  for (const std::string& s : {c, d})
    ASSERT_EQ(runTool("pcl_ls3d_convert", s + " " + s.substr(0, s.size() - 3) + "pcd",
                      dir.path.string()).code, 0);
  const pcl_ls3d_test::ToolRun strips = runTool(
      "pcl_ls3d_strip_adjust", dir.file("c.pcd") + " " + dir.file("d.pcd") + " -o " + dir.file("out"),
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
  ASSERT_EQ(runTool("pcl_ls3d_convert", utm + " " + dir.file("utm.pcd"), dir.path.string()).code,
            0);
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
    EXPECT_NE((r.out + r.err).find("'" + utm + "' declares WGS 84 / UTM zone 31N, '" + lambert +
                                   "' RGF93 v1 / Lambert-93"),
              std::string::npos)
        << r.out << r.err;
  }
  const pcl_ls3d_test::ToolRun pcd =
      runTool("pcl_ls3d_register", dir.file("utm.pcd") + " " + lambert, dir.path.string());
  EXPECT_NE(pcd.err.find("utm.pcd' declares WGS 84 / UTM zone 31N"), std::string::npos) << pcd.err;
}

// A compound CRS whose heights are in another unit than its plan coordinates (NAD83 / Oregon
// LCC in metres + NAVD88 height in US feet, as PDAL's autzen-bmx files) is said so: distances,
// rotations and residuals would mix the units. One unit throughout: nothing said.
TEST(ToolsWarnOfMixedUnits, HeightsInFeetOverMetres)
{
  const std::string mixed_crs = pcl_ls3d::maps::crsFromUserInput("EPSG:32631+6360");
  ASSERT_FALSE(mixed_crs.empty());
  ASSERT_NEAR(pcl_ls3d::maps::crsVerticalUnit(mixed_crs), 0.3048006, 1e-6);
  EXPECT_TRUE(pcl_ls3d::maps::crsMixesUnits(mixed_crs));
  EXPECT_FALSE(pcl_ls3d::maps::crsMixesUnits(pcl_ls3d::maps::crsFromUserInput("EPSG:2154+5720")));
  const TempDir dir("ls3d_mixed_units");
  const std::string a = dir.file("a.las"), b = dir.file("b.las");
  writePatch(a, "EPSG:32631+6360", 1.0, 0.0f);
  writePatch(b, "EPSG:32631+6360", 1.0, 0.2f);
  const std::string said = "'" + a + "' declares heights in ft and plan coordinates in m";
  const std::string calls[][2] = {
      {"pcl_ls3d_register", b + " " + a},
      {"pcl_ls3d_deformation", a + " " + b},
      {"pcl_ls3d_strip_adjust", a + " " + b + " -o " + dir.file("out")},
  };
  for (const auto& call : calls) {
    SCOPED_TRACE(call[0]);
    const pcl_ls3d_test::ToolRun r = runTool(call[0], call[1], dir.path.string());
    EXPECT_NE(r.code, 1) << r.err;
    EXPECT_NE((r.out + r.err).find(said), std::string::npos) << r.out << r.err;
  }
}
