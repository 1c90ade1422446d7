/// \file pcl_ls3d_info.cpp
/// \brief Prints what pcl_ls3d's readers see in a point-cloud file: format, counts, local origin,
///        bounds, the LAS header, the classification histogram (a SEGMENTS.pcd: its segment
///        count) and the flight strips. Every file is reported; exit 1 if any failed to load.
///        Bounds are in the file's global frame: a PCD whose header records a pcl_ls3d origin
///        (a SEGMENTS.pcd holds local floats) is read in it by io::loadCloud, and the text says so.

#include "tool_options.h"
#include "tool_output.h"

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/json_text.h>
#include <pcl_ls3d/io/strip_tools.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/segmentation/object_classes.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>
#include <pcl/io/pcd_io.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace pcl::console;

namespace {

void
printHelp(const char* name)
{
  print_error("Syntax is: %s file.{las,laz,copc.laz,pcd,ply,xyz,txt,csv} [more files] <options>\n", name);
  print_info("  where options are:\n");
  print_info("    -columns x,y,z,... : column names of ASCII XYZ inputs (see pcl_ls3d_convert -h)\n");
  print_info("    -bounds xmin,ymin,xmax,ymax[,zmin,zmax] : describe only the points in this box\n"
             "                         (file coordinates); a COPC file decodes only the octree\n"
             "                         nodes the box meets, and says how many\n");
  print_info("    -level N           : with -bounds on COPC: octree levels 0..N only\n");
  print_info("    -json              : print one JSON object per file instead of text\n");
  print_info("    -h                 : this help\n");
  print_info("  Every file is described; one error line per file that cannot be read (exit 1).\n"
             "  LAZ: the compressor, chunk size and count, and the items; COPC: the octree's\n"
             "  nodes, levels and points per level.\n");
}

// A SEGMENTS.pcd's labels are segment ids + 1 (0: in no segment), not classes; read as
// uint32 (the loader's classification is a byte and would wrap ids above 255).
nlohmann::json
describeSegments(const std::string& path)
{
  pcl::PointCloud<pcl::PointXYZRGBL> cloud;
  nlohmann::json s = {{"count", nullptr}, {"points_in_none", nullptr}};
  if (pcl::io::loadPCDFile(path, cloud) != 0)
    return s;
  std::set<std::uint32_t> ids;
  std::size_t none = 0;
  for (const auto& p : cloud) {
    if (p.label == 0)
      ++none;
    else
      ids.insert(p.label);
  }
  s["count"] = ids.size();
  s["points_in_none"] = none;
  return s;
}

const char*
compressorName(int compressor)
{
  switch (compressor) {
  case 1:
    return "pointwise";
  case 2:
    return "pointwise-chunked";
  case 3:
    return "layered-chunked";
  default:
    return "none";
  }
}

nlohmann::json
describeLaz(const pcl_ls3d::io::LazInfo& z)
{
  nlohmann::json j;
  j["compressor"] = compressorName(z.compressor);
  // 0xFFFFFFFF: chunks of varying size (COPC: one per octree node).
  j["chunk_size"] = z.chunk_size == 0xFFFFFFFFu ? nlohmann::json("variable") : nlohmann::json(z.chunk_size);
  j["chunk_count"] = z.chunk_count;
  j["chunk_table"] = z.chunk_table;
  j["items"] = z.items;
  return j;
}

nlohmann::json
describeCopc(const pcl_ls3d::io::CopcHeaderInfo& c)
{
  nlohmann::json j;
  j["center"] = {c.center[0], c.center[1], c.center[2]};
  j["halfsize"] = c.halfsize;
  j["spacing"] = c.spacing;
  j["nodes"] = c.nodes;
  j["levels"] = nlohmann::json::array();
  for (const auto& l : c.levels)
    j["levels"].push_back({{"level", l.level}, {"nodes", l.nodes}, {"points", l.points}});
  return j;
}

nlohmann::json
describeRegion(const pcl_ls3d::io::CloudInfo& info)
{
  nlohmann::json j;
  j["copc"] = info.region.copc;
  if (info.region.copc) {
    j["nodes"] = info.region.nodes;
    j["nodes_read"] = info.region.nodes_read;
  }
  j["points_decoded"] = info.region.points_decoded;
  j["points_outside"] = info.points_outside_region;
  return j;
}

std::vector<double>
vec(const Eigen::Vector3d& v)
{
  return std::vector<double>{v[0], v[1], v[2]};
}

/// The CRS a LAS declares in its VLRs, or a PCD / PLY the tools wrote records in its header.
void
describeCrs(const pcl_ls3d::io::CloudInfo& info, nlohmann::json& j)
{
  const std::string wkt = pcl_ls3d::maps::crsOfFile(info);
  if (wkt.empty())
    return;
  j[info.format == "las" ? "crs_declared" : "crs_recorded"] = pcl_ls3d::maps::crsName(wkt);
  j["crs_units"] = {{"plan", pcl_ls3d::maps::crsLinearUnitName(wkt)},
                    {"height", pcl_ls3d::maps::crsVerticalUnitName(wkt)},
                    {"plan_units_per_height_unit", pcl_ls3d::maps::planUnitsPerHeightUnit(wkt)}};
}

/// "USER/ID (N B)" per VLR.
std::vector<std::string>
vlrList(const std::vector<pcl_ls3d::io::LasVlr>& records)
{
  std::vector<std::string> out;
  for (const auto& v : records)
    out.push_back(v.user_id + "/" + std::to_string(v.record_id) + " (" + std::to_string(v.data.size()) +
                  " B)");
  return out;
}

/// The LAS header's fields and its VLRs.
nlohmann::json
describeLasHeader(const pcl_ls3d::io::LasHeaderInfo& h)
{
  nlohmann::json l;
  l["version"] = std::to_string(h.version_major) + "." + std::to_string(h.version_minor);
  l["point_format"] = h.point_format;
  l["record_length"] = h.record_length;
  l["extra_bytes_per_record"] = h.extra_bytes_per_record;
  l["header_size"] = h.header_size;
  l["offset_to_points"] = h.offset_to_points;
  l["global_encoding"] = h.global_encoding;
  l["system_identifier"] = h.system_identifier;
  l["generating_software"] = h.generating_software;
  l["scale"] = vec(h.scale);
  l["offset"] = vec(h.offset);
  l["header_min"] = vec(h.min);
  l["header_max"] = vec(h.max);
  l["vlrs"] = vlrList(h.vlrs);
  l["evlrs"] = vlrList(h.evlrs);
  return l;
}

/// Point counts per classification (a SEGMENTS.pcd's: its objects' classes, IMRG) and per
/// point-source id.
void
describeCounts(const pcl::PointCloud<pcl_ls3d::PointLiDAR>& cloud, const pcl_ls3d::io::CloudInfo& info,
               nlohmann::json& j)
{
  const bool segments = info.segments_file;
  if (!segments || info.hasField("classification")) {
    std::map<int, std::size_t> classes;
    for (const auto& p : cloud)
      ++classes[p.classification];
    for (const auto& [c, n] : classes)
      j[segments ? "object_classes" : "classes"][std::to_string(c)] = n;
  }
  for (const auto& [id, idx] : pcl_ls3d::io::splitByPointSource(cloud))
    j["point_source_ids"][std::to_string(id)] = idx.size();
}

nlohmann::json
describe(const std::string& path, const pcl::PointCloud<pcl_ls3d::PointLiDAR>& cloud,
         const pcl_ls3d::io::CloudInfo& info, double ms)
{
  nlohmann::json j;
  j["file"] = path;
  j["format"] = info.format;
  j["points_in_file"] = info.points_in_file;
  j["points_loaded"] = info.points_loaded;
  j["points_dropped_nonfinite"] = info.points_dropped_nonfinite;
  j["local_origin"] = vec(info.origin);
  // A SEGMENTS.pcd stores local floats (a float cannot hold projected coordinates): the reader
  // applied the origin its header records; say so, as the file itself is not in that frame.
  if (info.has_file_origin)
    j["origin_applied"] = vec(info.file_origin);
  describeCrs(info, j);
  j["min"] = vec(info.min_file);
  j["max"] = vec(info.max_file);
  j["fields"] = info.fields;
  if (info.format == "xyz")
    j["xyz_unmapped_columns"] = info.xyz_unmapped_columns;
  j["load_ms"] = ms;
  if (info.format == "las") {
    j["las"] = describeLasHeader(info.las);
    if (info.las.laz.compressed)
      j["laz"] = describeLaz(info.las.laz);
    if (info.las.copc.present)
      j["copc"] = describeCopc(info.las.copc);
  }
  if (info.region.applied)
    j["region"] = describeRegion(info);
  if (info.segments_file)
    j["segments"] = describeSegments(path);
  describeCounts(cloud, info, j);
  return j;
}

/// The CRS line: its name, where it comes from, and heights in another unit than the plan.
void
printCrs(const nlohmann::json& j)
{
  const bool declared = j.contains("crs_declared");
  if (!declared && !j.contains("crs_recorded"))
    return;
  print_info("  crs %s (%s)\n", j[declared ? "crs_declared" : "crs_recorded"].get<std::string>().c_str(),
             declared ? "declared in the LAS VLRs" : "recorded in the header");
  const std::string plan = j["crs_units"]["plan"], height = j["crs_units"]["height"];
  const double factor = j["crs_units"]["plan_units_per_height_unit"];
  if (factor != 1.0)  // US and international feet differ too, though both are "ft"
    print_info("  heights in %s, plan coordinates in %s (x %.7g): register, compare, deformation "
               "and the strip adjustment convert the heights to the plan unit\n",
               height.c_str(), plan.c_str(), factor);
}

/// The LAZ compression, the COPC octree and what a -bounds query read.
void
printLazAndCopc(const nlohmann::json& j)
{
  if (j.contains("laz")) {
    const auto& z = j["laz"];
    const std::string size =
        z["chunk_size"].is_string()
            ? "variable-size chunks"
            : "chunks of " + std::to_string(z["chunk_size"].get<std::uint64_t>()) + " points";
    print_info("  LAZ %s, %s, %zu chunks (chunk table %s); items %s\n",
               z["compressor"].get<std::string>().c_str(), size.c_str(), z["chunk_count"].get<std::size_t>(),
               z["chunk_table"].get<bool>() ? "read" : "missing: chunks walked",
               z["items"].get<std::string>().c_str());
  }
  if (j.contains("copc")) {
    const auto& c = j["copc"];
    std::string levels;
    for (const auto& l : c["levels"])
      levels += " " + std::to_string(l["level"].get<int>()) + ":" +
                std::to_string(l["nodes"].get<std::size_t>()) + "/" +
                std::to_string(l["points"].get<std::uint64_t>());
    print_info("  COPC octree: %zu nodes in %zu levels, spacing %g; per level (level:nodes/points):%s\n",
               c["nodes"].get<std::size_t>(), c["levels"].size(), c["spacing"].get<double>(), levels.c_str());
  }
  if (j.contains("region")) {
    const auto& r = j["region"];
    if (r["copc"].get<bool>())
      print_info("  -bounds: decoded %zu of %zu COPC nodes (%zu points), %zu points outside the box\n",
                 r["nodes_read"].get<std::size_t>(), r["nodes"].get<std::size_t>(),
                 r["points_decoded"].get<std::size_t>(), r["points_outside"].get<std::size_t>());
    else
      print_info("  -bounds: read all %zu points, %zu outside the box\n",
                 r["points_decoded"].get<std::size_t>(), r["points_outside"].get<std::size_t>());
  }
}

void
printText(const nlohmann::json& j)
{
  print_info("%s\n", j["file"].get<std::string>().c_str());
  print_info("  format %s, points in file %zu, loaded %zu, NaN/inf dropped %zu (%.1f ms)\n",
             j["format"].get<std::string>().c_str(), j["points_in_file"].get<std::size_t>(),
             j["points_loaded"].get<std::size_t>(), j["points_dropped_nonfinite"].get<std::size_t>(),
             j["load_ms"].get<double>());
  const auto o = j["local_origin"].get<std::vector<double>>();
  const auto lo = j["min"].get<std::vector<double>>(), hi = j["max"].get<std::vector<double>>();
  // A recorded origin is the local origin too: one line, saying where it came from.
  printCrs(j);
  if (j.contains("origin_applied")) {
    const auto f = j["origin_applied"].get<std::vector<double>>();
    print_info("  origin %.3f %.3f %.3f applied (local float coordinates in the file)\n", f[0], f[1], f[2]);
  } else {
    print_info("  local origin %.3f %.3f %.3f\n", o[0], o[1], o[2]);
  }
  print_info("  bounds min %.3f %.3f %.3f  max %.3f %.3f %.3f\n", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  std::string fields;
  for (const auto& f : j["fields"])
    fields += " " + f.get<std::string>();
  if (j.value("xyz_unmapped_columns", std::size_t(0)) > 0)
    fields += " (+" + std::to_string(j["xyz_unmapped_columns"].get<std::size_t>()) +
              " unmapped columns; name them with -columns)";
  print_info("  fields:%s\n", fields.c_str());
  if (j.contains("las")) {
    const auto& l = j["las"];
    const auto s = l["scale"].get<std::vector<double>>(), off = l["offset"].get<std::vector<double>>();
    print_info("  LAS %s, point format %d, record %d B (%d extra), header %d B, points at %u, "
               "global encoding %d\n",
               l["version"].get<std::string>().c_str(), l["point_format"].get<int>(),
               l["record_length"].get<int>(), l["extra_bytes_per_record"].get<int>(),
               l["header_size"].get<int>(), l["offset_to_points"].get<unsigned>(),
               l["global_encoding"].get<int>());
    print_info("  scale %g %g %g, offset %.3f %.3f %.3f, software \"%s\"\n", s[0], s[1], s[2], off[0], off[1],
               off[2], l["generating_software"].get<std::string>().c_str());
    for (const auto& v : l["vlrs"])
      print_info("  VLR %s\n", v.get<std::string>().c_str());
    for (const auto& v : l["evlrs"])
      print_info("  EVLR %s\n", v.get<std::string>().c_str());
  }
  printLazAndCopc(j);
  if (j.contains("segments")) {
    const auto& s = j["segments"];
    if (s["count"].is_null())
      print_info("  labels are segment ids (pcl_ls3d_segment output), not classes\n");
    else
      print_info("  labels are segment ids (pcl_ls3d_segment output), not classes: %zu segments, "
                 "%zu points in none\n",
                 s["count"].get<std::size_t>(), s["points_in_none"].get<std::size_t>());
  }
  for (const char* key : {"classes", "object_classes"}) {
    if (!j.contains(key))
      continue;
    std::string classes;
    for (const auto& [c, n] : j[key].items())
      classes += " " + c + ":" + std::to_string(n.get<std::size_t>());
    const bool objects = std::string(key) == "object_classes";
    const std::string codes =
        objects ? " (" + pcl_ls3d::segmentation::describeLasCodes() + ", 0 no segment)" : "";
    print_info("  %s:%s%s\n", objects ? "object classes (LAS codes)" : "classes", classes.c_str(),
               codes.c_str());
  }
  std::string strips;
  for (const auto& [id, n] : j["point_source_ids"].items())
    strips += " " + id + ":" + std::to_string(n.get<std::size_t>());
  print_info("  point source ids:%s\n", strips.c_str());
}

}  // namespace

int
main(int argc, char** argv)
{
  pcl_ls3d::tools::lineBufferedStdout();
  if (argc < 2 || find_switch(argc, argv, "-h") || find_switch(argc, argv, "--help")) {
    printHelp(argv[0]);
    return argc < 2 ? 1 : 0;
  }
  pcl_ls3d::io::LoadOptions options;
  std::vector<std::string> files;
  std::string why;
  if (!pcl_ls3d::tools::splitArguments(argc, argv, 1, {"-columns", "-bounds", "-level"}, {"-json"}, files,
                                       why) ||
      !pcl_ls3d::tools::regionOptions(argc, argv, options.region, why)) {
    print_error("%s\n", why.c_str());
    return 1;
  }
  parse_argument(argc, argv, "-columns", options.xyz_columns);
  const bool json = find_switch(argc, argv, "-json");
  if (files.empty()) {
    print_error("No input file given (see -h).\n");
    return 1;
  }
  std::size_t failed = 0;  // a bad file does not hide the others
  for (const auto& path : files) {
    pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
    pcl_ls3d::io::CloudInfo info;
    std::string error;
    TicToc tt;
    tt.tic();
    if (!pcl_ls3d::io::loadCloud(path, cloud, info, error, options)) {
      print_error("Cannot load %s\n", error.c_str());
      ++failed;
      continue;
    }
    const nlohmann::json j = describe(path, cloud, info, tt.toc());
    if (json)
      std::cout << pcl_ls3d::io::toJsonText(j) << std::endl;
    else
      printText(j);
  }
  return failed > 0 ? 1 : 0;
}
