// -map_format in the tools that draw maps: pcl_ls3d_deformation writes PREFIX.pdf or .svg beside
// the GeoTIFF (and no PNG), pcl_ls3d_strip_adjust writes every map and histogram in the format
// asked; an unknown format or an unwritable map is refused with one error line, a non-zero exit
// and no output.
#include "../io/tool_run.h"
#include "maps/vector_files.h"

#include <pcl_ls3d/strips/strip_files.h>
#include <pcl_ls3d/synth/li_surface.h>

#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;
using pcl_ls3d_test::lineCount;
using pcl_ls3d_test::runTool;
using pcl_ls3d_test::slurpBytes;

namespace {

struct Scratch
{
  fs::path dir = fs::temp_directory_path() / ("pcl_ls3d_map_format_tools_" + std::to_string(::getpid()));
  Scratch()
  {
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
};

/// Li's surface with 20 % raised at the lower right, as s/ref.pcd and s/epoch.pcd.
void
writeLiPair(const Scratch& s)
{
  pcl_ls3d::synth::LiSurfaceSettings ls;
  ls.deformation_percent = 20.0;
  ls.deformation_c = 10.0;
  ls.position = pcl_ls3d::synth::DeformationPosition::LOWER_RIGHT;
  const pcl_ls3d::synth::LiSurface li = pcl_ls3d::synth::makeLiSurface(ls);
  pcl::PointCloud<pcl::PointXYZ> ref, mate;
  pcl::copyPointCloud(*li.reference, ref);
  pcl::copyPointCloud(*li.mate, mate);
  ASSERT_EQ(pcl::io::savePCDFileBinary(s.file("ref.pcd"), ref), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinary(s.file("epoch.pcd"), mate), 0);
}

}  // namespace

TEST(MapFormatTools, DeformationWritesTheFormatAsked)
{
  const Scratch s;
  writeLiPair(s);
  const std::string pair = s.file("ref.pcd") + " " + s.file("epoch.pcd");
  auto r =
      runTool("pcl_ls3d_deformation", pair + " -map " + s.file("m") + " -map_format pdf", s.dir.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurpBytes(s.file("m.pdf")).compare(0, 5, "%PDF-"), 0);
  EXPECT_TRUE(fs::exists(s.file("m.tif")));
  EXPECT_FALSE(fs::exists(s.file("m.png")));
  EXPECT_NE(r.out.find("m.pdf"), std::string::npos) << r.out;
  std::string text;
  for (const std::string& t : pcl_ls3d_test::pdfText(slurpBytes(s.file("m.pdf"))))
    text += t;
  EXPECT_NE(text.find("Deformation: epoch.pcd against ref.pcd"), std::string::npos) << text;
  EXPECT_NE(text.find("outline: deformed region"), std::string::npos) << text;

  r = runTool("pcl_ls3d_deformation", pair + " -map " + s.file("v") + " -map_format svg", s.dir.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::string why;
  EXPECT_TRUE(pcl_ls3d_test::wellFormedXml(slurpBytes(s.file("v.svg")), why)) << why;

  // Refused before the inputs are read: one line, exit 1, nothing written.
  for (const std::string& bad :
       {" -map " + s.file("x") + " -map_format jpg", " -map " + s.file("x") + " -map_format",
        " -map " + s.file("no_such_folder/x") + " -map_format svg", std::string(" -map_format pdf")}) {
    r = runTool("pcl_ls3d_deformation", pair + bad, s.dir.string());
    EXPECT_EQ(r.code, 1) << bad;
    EXPECT_EQ(lineCount(r.err), 1u) << bad << ": " << r.err;
  }
  EXPECT_NE(
      runTool("pcl_ls3d_deformation", pair + " -map " + s.file("x") + " -map_format jpg", s.dir.string())
          .err.find("-map_format"),
      std::string::npos);
  EXPECT_NE(runTool("pcl_ls3d_deformation", pair + " -map_format pdf", s.dir.string()).err.find("needs -map"),
            std::string::npos);
  for (const char* name : {"x.png", "x.jpg", "x.tif", "x.svg"})
    EXPECT_FALSE(fs::exists(s.file(name))) << name;
  // An existing map is kept without -overwrite.
  r = runTool("pcl_ls3d_deformation", pair + " -map " + s.file("v") + " -map_format svg", s.dir.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("v.svg"), std::string::npos) << r.err;
}

TEST(MapFormatTools, StripAdjustWritesEveryMapInTheFormatAsked)
{
  const Scratch s;
  auto r = runTool("pcl_ls3d_synth",
                   "strips -o '" + s.file("in") +
                       "' -format las -split -strips 2 -length 160 -swath 100 "
                       "-density 1 -seed 5 -shift_sigma 0.3 -angle_sigma 5e-4 -scale_sigma 0",
                   s.dir.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string input = "'" + s.file("in/strips.las") + "' -split psid -reference 1";
  r = runTool("pcl_ls3d_strip_adjust", input + " -maps '" + s.file("maps") + "' -map_format svg",
              s.dir.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::size_t svg = 0, png = 0, tif = 0;
  for (const auto& e : fs::directory_iterator(s.file("maps"))) {
    svg += e.path().extension() == ".svg";
    png += e.path().extension() == ".png";
    tif += e.path().extension() == ".tif";
  }
  // Per overlap: before, after, histogram; the mosaic before and after and the block histogram.
  EXPECT_EQ(svg, 6u);
  EXPECT_EQ(tif, 4u);
  EXPECT_EQ(png, 0u);
  std::string why;
  EXPECT_TRUE(pcl_ls3d_test::wellFormedXml(slurpBytes(s.file("maps/histogram.svg")), why)) << why;

  r = runTool("pcl_ls3d_strip_adjust", input + " -maps '" + s.file("maps2") + "' -map_format tiff",
              s.dir.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("-map_format"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(s.file("maps2")));
  r = runTool("pcl_ls3d_strip_adjust", input + " -map_format pdf", s.dir.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("needs -maps"), std::string::npos) << r.err;
}

// The staged strip adjustment carries the format in its plan file; a plan written before the
// option existed (no map_format) draws PNG, and an unknown format is refused when read.
TEST(MapFormatTools, StripPlanFileCarriesTheFormat)
{
  const Scratch s;
  pcl_ls3d::strips::PlanFile plan;
  plan.map_format = pcl_ls3d::maps::MapFormat::SVG;
  std::string error;
  ASSERT_TRUE(pcl_ls3d::strips::writePlanFile(s.file("plan.json"), plan, error)) << error;
  pcl_ls3d::strips::PlanFile back;
  ASSERT_TRUE(pcl_ls3d::strips::readPlanFile(s.file("plan.json"), back, error)) << error;
  EXPECT_EQ(back.map_format, pcl_ls3d::maps::MapFormat::SVG);

  nlohmann::json j = nlohmann::json::parse(slurpBytes(s.file("plan.json")));
  j.erase("map_format");
  std::ofstream(s.file("old.json")) << j.dump();
  ASSERT_TRUE(pcl_ls3d::strips::readPlanFile(s.file("old.json"), back, error)) << error;
  EXPECT_EQ(back.map_format, pcl_ls3d::maps::MapFormat::PNG);

  j["map_format"] = "gif";
  std::ofstream(s.file("bad.json")) << j.dump();
  EXPECT_FALSE(pcl_ls3d::strips::readPlanFile(s.file("bad.json"), back, error));
  EXPECT_NE(error.find("map_format"), std::string::npos) << error;
}
