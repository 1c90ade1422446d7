/// \file test_laz_tools.cpp
/// \brief LAZ and COPC through the tools: pcl_ls3d_convert converts LAS <-> LAZ losslessly
///        (records, VLRs and EVLRs byte for byte; the LASzip VLR added or removed) and crops
///        with -bounds (a COPC input decodes only the nodes the box meets); pcl_ls3d_info
///        reports the compression and the COPC octree; every LAZ file of shared/data loads; and
///        each tool that takes a cloud runs on a LAZ input.

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/las_io.h>
#include <pcl_ls3d/strips/strip_io.h>

#include "io/io_test_utils.h"
#include "io/laz_test_utils.h"
#include "io/tool_json.h"
#include "io/tool_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

using namespace pcl_ls3d;
using pcl_ls3d_test::readBytes;
using pcl_ls3d_test::runTool;
using pcl_ls3d_test::sharedData;
namespace fs = std::filesystem;

namespace {

/// The parts of a LAS file a lossless conversion keeps: records, VLRs and EVLRs (the LASzip VLR
/// left out, it describes one encoding only).
struct LasParts
{
  std::vector<std::uint8_t> records;
  std::vector<std::string> vlrs, evlrs;  // user / id / description / payload, as bytes
  bool compressed = false;
};

std::string
vlrKey(const io::LasVlr& v)
{
  return v.user_id + "|" + std::to_string(v.record_id) + "|" + v.description + "|" +
         std::string(v.data.begin(), v.data.end());
}

LasParts
partsOf(const std::string& path)
{
  const std::vector<std::uint8_t> bytes = readBytes(path);
  LasParts p;
  io::LasHeaderInfo h;
  std::string error;
  EXPECT_TRUE(io::readLasHeader(bytes.data(), bytes.size(), h, error)) << path << ": " << error;
  p.compressed = h.laz.compressed;
  p.records = h.laz.compressed ? pcl_ls3d_test::lazRecords(bytes, h) : pcl_ls3d_test::lasRecords(bytes, h);
  for (const io::LasVlr& v : h.vlrs)
    if (v.user_id != "laszip encoded")
      p.vlrs.push_back(vlrKey(v));
  for (const io::LasVlr& v : h.evlrs)
    p.evlrs.push_back(vlrKey(v));
  return p;
}

std::string
quoted(const std::string& path)
{
  return "'" + path + "'";
}

/// LAS -> LAZ -> LAS with pcl_ls3d_convert: the LAZ is compressed, and both keep the original's
/// records, VLRs and EVLRs byte for byte; returns the LAS written back.
std::string
roundTrip(const std::string& las, const pcl_ls3d_test::TempDir& dir, const std::string& stem)
{
  const std::string laz = dir.file(stem + ".laz"), back = dir.file(stem + "_back.las");
  auto r = runTool("pcl_ls3d_convert", quoted(las) + " " + quoted(laz), dir.path.string());
  EXPECT_EQ(r.code, 0) << r.err;
  r = runTool("pcl_ls3d_convert", quoted(laz) + " " + quoted(back), dir.path.string());
  EXPECT_EQ(r.code, 0) << r.err;
  const LasParts a = partsOf(las), z = partsOf(laz), b = partsOf(back);
  EXPECT_FALSE(a.compressed);
  EXPECT_TRUE(z.compressed);
  EXPECT_FALSE(b.compressed);
  EXPECT_FALSE(a.records.empty());
  for (const LasParts* p : {&z, &b}) {
    EXPECT_TRUE(p->records == a.records);
    EXPECT_EQ(p->vlrs, a.vlrs);
    EXPECT_EQ(p->evlrs, a.evlrs);
  }
  return back;
}

}  // namespace

// Generated LAS files (formats 1, 3, 6, 8, with a CRS VLR): LAS -> LAZ -> LAS gives the original
// file back byte for byte, header included.
TEST(LazTools, ConvertLasLazLasIsLosslessOnGeneratedFiles)
{
  pcl_ls3d_test::TempDir dir("ls3d_laz_tools_gen");
  for (int format : {1, 3, 6, 8}) {
    SCOPED_TRACE("format " + std::to_string(format));
    pcl::PointCloud<PointLiDAR> cloud;
    std::vector<Eigen::Vector3d> truth;
    pcl_ls3d_test::makeUtmCloud(2500, format, {500100.0, 5000100.0, 50.0}, {500000.0, 5000000.0, 0.0}, cloud,
                                truth);
    io::SaveOptions so;
    so.las_point_format = static_cast<std::uint8_t>(format);
    so.las_minor_version = format >= 6 ? 4 : 2;
    so.las_vlrs.push_back({"pcl_ls3d_test", 7, "a VLR to keep", {1, 2, 3, 4, 5}});
    const std::string las = dir.file("pf" + std::to_string(format) + ".las");
    std::string error;
    ASSERT_TRUE(io::saveCloud(las, cloud, {500000.0, 5000000.0, 0.0}, error, so)) << error;
    const std::string back = roundTrip(las, dir, "pf" + std::to_string(format));
    EXPECT_TRUE(readBytes(back) == readBytes(las));
  }
}

// -classes and -bounds on LAS/LAZ records: the output holds exactly the input's records of those
// classes inside the box, byte for byte and in file order, whichever of LAS and LAZ goes in or
// out; the header counts follow (the points of the file's other classes are gone).
TEST(LazTools, ConvertSelectsRecordsLosslessly)
{
  pcl_ls3d_test::TempDir dir("ls3d_laz_tools_select");
  pcl::PointCloud<PointLiDAR> cloud;
  std::vector<Eigen::Vector3d> truth;
  const Eigen::Vector3d base(500100.0, 5000100.0, 50.0), origin(500000.0, 5000000.0, 0.0);
  pcl_ls3d_test::makeUtmCloud(4000, 8, base, origin, cloud, truth);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    cloud[i].classification = static_cast<std::uint8_t>(i % 4 == 0 ? 2 : 6);
  io::SaveOptions so;
  so.las_point_format = 8;
  so.las_minor_version = 4;
  std::string error;
  ASSERT_TRUE(io::saveCloud(dir.file("in.las"), cloud, origin, error, so)) << error;
  ASSERT_TRUE(io::saveCloud(dir.file("in.laz"), cloud, origin, error, so)) << error;
  const LasParts in = partsOf(dir.file("in.las"));
  const std::size_t length = in.records.size() / cloud.size();
  const double x0 = base.x() - 100.0, x1 = base.x() + 250.0;
  std::vector<std::uint8_t> expected;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (cloud[i].classification == 2 && truth[i].x() >= x0 && truth[i].x() <= x1)
      expected.insert(expected.end(), in.records.begin() + i * length, in.records.begin() + (i + 1) * length);
  ASSERT_GT(expected.size(), 50 * length);
  const std::string args = " -classes 2 -bounds " + std::to_string(x0) + ",0," + std::to_string(x1) + ",1e8";
  for (const auto& [from, to] :
       {std::pair<const char*, const char*>{"in.las", "a.laz"}, {"in.laz", "b.las"}, {"in.laz", "c.laz"}}) {
    SCOPED_TRACE(std::string(from) + " -> " + to);
    const auto r = runTool("pcl_ls3d_convert", quoted(dir.file(from)) + " " + quoted(dir.file(to)) + args,
                           dir.path.string());
    ASSERT_EQ(r.code, 0) << r.err;
    const LasParts out = partsOf(dir.file(to));
    EXPECT_EQ(out.compressed, std::string(to).find(".laz") != std::string::npos);
    EXPECT_TRUE(out.records == expected);
    EXPECT_EQ(out.vlrs, in.vlrs);
    pcl::PointCloud<PointLiDAR> back;
    io::CloudInfo info;
    ASSERT_TRUE(io::loadCloud(dir.file(to), back, info, error)) << error;
    EXPECT_EQ(info.las.point_count, expected.size() / length);
  }
}

// Real twins: simple.las (LAS 1.2, PF3) and 1_4_w_evlr.las (LAS 1.4 with EVLRs) round trip;
// the LASzip-written LAZ twins convert to LAS with their twins' records, VLRs and EVLRs.
TEST(LazTools, ConvertLasLazLasIsLosslessOnRealTwins)
{
  const std::string simple = sharedData("laz/laspy/simple.las");
  PCL_LS3D_REQUIRE_DATA(simple);
  pcl_ls3d_test::TempDir dir("ls3d_laz_tools_real");
  for (const char* stem : {"simple", "1_4_w_evlr"}) {
    SCOPED_TRACE(stem);
    const std::string las = sharedData(std::string("laz/laspy/") + stem + ".las");
    roundTrip(las, dir, stem);
    const std::string out = dir.file(std::string(stem) + "_from_laszip.las");
    const auto r = runTool("pcl_ls3d_convert",
                           quoted(sharedData(std::string("laz/laspy/") + stem + ".laz")) + " " + quoted(out),
                           dir.path.string());
    ASSERT_EQ(r.code, 0) << r.err;
    const LasParts a = partsOf(las), b = partsOf(out);
    EXPECT_TRUE(a.records == b.records);
    EXPECT_EQ(a.vlrs, b.vlrs);
    EXPECT_EQ(a.evlrs, b.evlrs);
  }
  EXPECT_FALSE(partsOf(sharedData("laz/laspy/1_4_w_evlr.las")).evlrs.empty());
}

// -bounds on COPC: only the nodes the box meets are decoded (the tool says how many), and the
// output holds exactly the records of the whole file inside the box; the same crop of the LAZ
// twin (another point format, so compared by coordinates) holds the same points.
TEST(LazTools, ConvertBoundsOnCopcDecodesOnlyTheNodesItNeeds)
{
  const std::string copc = sharedData("laz/pdal/lone-star.copc.laz");
  PCL_LS3D_REQUIRE_DATA(copc);
  pcl_ls3d_test::TempDir dir("ls3d_laz_tools_bounds");
  io::LasHeaderInfo h;
  const std::vector<std::uint8_t> bytes = readBytes(copc);
  std::string error;
  ASSERT_TRUE(io::readLasHeader(bytes.data(), bytes.size(), h, error)) << error;
  const Eigen::Vector3d lo = h.min, mid = 0.5 * (h.min + h.max);
  char bounds[256];
  std::snprintf(bounds, sizeof(bounds), "%.3f,%.3f,%.3f,%.3f", lo.x(), lo.y(), mid.x(), mid.y());
  const std::string out = dir.file("crop.laz");
  auto r =
      runTool("pcl_ls3d_convert", quoted(copc) + " " + quoted(out) + " -bounds " + bounds, dir.path.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::size_t read = 0, nodes = 0;
  ASSERT_EQ(
      std::sscanf(r.out.substr(r.out.find("Decoded")).c_str(), "Decoded %zu of %zu COPC", &read, &nodes), 2)
      << r.out;
  EXPECT_LT(read, nodes);
  EXPECT_EQ(nodes, h.copc.nodes);
  // The truth: every record of the whole file inside the box (read to 1e-3 file units: the
  // printed bounds are rounded so, and the reader compares in double).
  io::Region region;
  ASSERT_EQ(std::sscanf(bounds, "%lf,%lf,%lf,%lf", &region.box.min().x(), &region.box.min().y(),
                        &region.box.max().x(), &region.box.max().y()),
            4);
  std::vector<std::uint8_t> las;
  ASSERT_TRUE(io::decompressLaz(bytes.data(), bytes.size(), las, error)) << error;
  io::LasHeaderInfo plain;
  const std::vector<std::uint8_t> all = pcl_ls3d_test::lasRecords(las, plain);
  std::vector<std::string> truth, got;
  for (std::size_t at = 0; at < all.size(); at += plain.record_length) {
    std::int32_t q[2];
    std::memcpy(q, all.data() + at, 8);
    const double x = q[0] * plain.scale[0] + plain.offset[0], y = q[1] * plain.scale[1] + plain.offset[1];
    if (x >= region.box.min().x() && x <= region.box.max().x() && y >= region.box.min().y() &&
        y <= region.box.max().y())
      truth.emplace_back(reinterpret_cast<const char*>(all.data() + at), plain.record_length);
  }
  const LasParts cropped = partsOf(out);
  for (std::size_t at = 0; at < cropped.records.size(); at += plain.record_length)
    got.emplace_back(reinterpret_cast<const char*>(cropped.records.data() + at), plain.record_length);
  std::sort(truth.begin(), truth.end());
  std::sort(got.begin(), got.end());
  EXPECT_GT(truth.size(), 1000u);
  EXPECT_TRUE(got == truth);
  // The output is a plain LAZ file: no COPC VLR or hierarchy left to misdescribe it.
  for (const std::string& v : cropped.vlrs)
    EXPECT_NE(v.rfind("copc|", 0), 0u);
  EXPECT_TRUE(cropped.evlrs.empty());
  // The pointwise LAZ twin (PF1), cropped by the same box into a PCD: as many points.
  r = runTool("pcl_ls3d_convert",
              quoted(sharedData("laz/pdal/lone-star.laz")) + " " + quoted(dir.file("crop.pcd")) +
                  " -bounds " + bounds,
              dir.path.string());
  ASSERT_EQ(r.code, 0) << r.err;
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  ASSERT_TRUE(io::loadCloud(dir.file("crop.pcd"), cloud, info, error)) << error;
  EXPECT_EQ(cloud.size(), truth.size());
  // pcl_ls3d_info -bounds says the same count of nodes.
  r = runTool("pcl_ls3d_info", quoted(copc) + " -bounds " + bounds + " -json", dir.path.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["region"]["nodes_read"].get<std::size_t>(), read);
  EXPECT_EQ(j["points_loaded"].get<std::size_t>(), truth.size());
}

// pcl_ls3d_info on LAZ and COPC: compressor, chunk size and count; the octree's nodes, levels
// and points per level, which add up to the file's points.
TEST(LazTools, InfoReportsCompressionAndTheCopcOctree)
{
  const std::string copc = sharedData("laz/pdal/lone-star.copc.laz");
  const std::string laz = sharedData("laz/pdal/autzen_trim.laz");
  PCL_LS3D_REQUIRE_DATA(copc);
  pcl_ls3d_test::TempDir dir("ls3d_laz_tools_info");
  auto r = runTool("pcl_ls3d_info", quoted(copc) + " " + quoted(laz) + " -json", dir.path.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string line;
  std::vector<nlohmann::json> js;
  while (std::getline(lines, line))
    if (!line.empty())
      js.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(js.size(), 2u) << r.out;
  const nlohmann::json& c = js[0];
  EXPECT_EQ(c["laz"]["compressor"], "layered-chunked");
  EXPECT_EQ(c["laz"]["chunk_size"], "variable");
  ASSERT_TRUE(c.contains("copc"));
  std::size_t nodes = 0;
  std::uint64_t points = 0;
  for (const auto& l : c["copc"]["levels"]) {
    nodes += l["nodes"].get<std::size_t>();
    points += l["points"].get<std::uint64_t>();
  }
  EXPECT_EQ(nodes, c["copc"]["nodes"].get<std::size_t>());
  EXPECT_EQ(points, c["points_in_file"].get<std::uint64_t>());
  EXPECT_EQ(c["laz"]["chunk_count"].get<std::size_t>(), nodes);  // one chunk per node
  const nlohmann::json& z = js[1];
  EXPECT_EQ(z["laz"]["compressor"], "pointwise-chunked");
  EXPECT_EQ(z["laz"]["chunk_size"].get<std::uint32_t>(), 50000u);
  EXPECT_EQ(z["laz"]["chunk_count"].get<std::size_t>(), 3u);  // 110 000 points
  EXPECT_FALSE(z.contains("copc"));
  r = runTool("pcl_ls3d_info", quoted(copc), dir.path.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("COPC octree: " + std::to_string(nodes) + " nodes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("LAZ layered-chunked, variable-size chunks"), std::string::npos) << r.out;
}

// Every LAZ and COPC file of shared/data/laz loads (loadCloud, which every tool uses) with all
// its points.
TEST(LazTools, EveryLazFileOfTheSharedDataLoads)
{
  const std::string root = sharedData("laz");
  PCL_LS3D_REQUIRE_DATA(root);
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (io::fileExtension(entry.path().string()) != "laz")
      continue;
    SCOPED_TRACE(entry.path().string());
    ++files;
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(io::loadCloud(entry.path().string(), cloud, info, error)) << error;
    EXPECT_TRUE(info.las.laz.compressed);
    EXPECT_EQ(cloud.size(), info.las.point_count);
    EXPECT_GT(cloud.size(), 0u);
  }
  EXPECT_GE(files, 20u);
}

// Each tool that takes a cloud runs on a LAZ (or COPC) input.
TEST(LazTools, EveryToolReadsLaz)
{
  const std::string tile = sharedData("laz/ign/las_with_origin_dsmMarker.laz");
  const std::string small = sharedData("laz/ign/target_cloud_crop.laz");
  const std::string copc = sharedData("laz/laspy/simple.copc.laz");
  PCL_LS3D_REQUIRE_DATA(tile);
  pcl_ls3d_test::TempDir dir("ls3d_laz_tools_smoke");
  const std::string d = dir.path.string();
  struct Run
  {
    const char* tool;
    std::string args;
    std::vector<int> codes;  // accepted exit codes (an adjustment may legitimately refuse)
  };
  const std::vector<Run> runs = {
      {"pcl_ls3d_info", quoted(copc) + " " + quoted(tile), {0}},
      {"pcl_ls3d_convert", quoted(copc) + " " + quoted(dir.file("c.pcd")), {0}},
      {"pcl_ls3d_register",
       quoted(small) + " " + quoted(small) + " -max_iter 3 -o " + quoted(dir.file("aligned.laz")),
       {0}},
      {"pcl_ls3d_compare", quoted(small) + " " + quoted(small) + " -methods ls3d-lnd -iter 3", {0}},
      {"pcl_ls3d_deformation", quoted(small) + " " + quoted(small), {0}},
      {"pcl_ls3d_segment", quoted(small) + " -o " + quoted(dir.file("SEGMENTS.pcd")), {0}},
      {"pcl_ls3d_strip_adjust", quoted(tile) + " -split psid -q -o " + quoted(dir.file("strips")), {0, 3}},
      {"pcl_ls3d_synth", "pair -o " + quoted(dir.file("synth")) + " -format laz", {0}},
  };
  for (const Run& run : runs) {
    SCOPED_TRACE(run.tool);
    const auto r = runTool(run.tool, run.args, d);
    EXPECT_NE(std::find(run.codes.begin(), run.codes.end(), r.code), run.codes.end())
        << "exit " << r.code << "\n"
        << r.err << r.out.substr(0, 2000);
  }
  // What they wrote as LAZ is LAZ, and loads.
  for (const std::string& f :
       {dir.file("aligned.laz"), dir.file("strips/las_with_origin_dsmMarker_psid3025.laz")}) {
    SCOPED_TRACE(f);
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(io::loadCloud(f, cloud, info, error)) << error;
    EXPECT_TRUE(info.las.laz.compressed);
  }
  std::size_t synth_laz = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir.file("synth")))
    synth_laz += e.path().extension() == ".laz";
  EXPECT_GE(synth_laz, 2u);
}

// The strip adjustment writes a corrected COPC strip as plain LAZ, named so: "x.copc.laz" gives
// "x.laz" (or "x_psid<ID>.laz"); other names keep their stem and extension.
TEST(LazTools, CorrectedCopcStripsAreNamedLaz)
{
  strips::LoadedStrips block;
  block.inputs.resize(3);
  block.inputs[0].path = "in/a.copc.laz";
  block.inputs[1].path = "in/b.laz";
  block.inputs[2].path = "in/c.copc.las";
  for (auto& f : block.inputs)
    f.point_sources = {{7, 10}};
  block.sources.resize(1);
  std::vector<std::string> whole, split;
  for (const auto& u : strips::outputUnits(block, "out", false))
    whole.push_back(u.path);
  block.sources[0].point_source_id = 7;
  for (const auto& u : strips::outputUnits(block, "out", false))
    split.push_back(u.path);
  EXPECT_EQ(whole, (std::vector<std::string>{"out/a.laz", "out/b.laz", "out/c.copc.las"}));
  EXPECT_EQ(split, (std::vector<std::string>{"out/a_psid7.laz", "out/b_psid7.laz", "out/c.copc_psid7.las"}));
}
