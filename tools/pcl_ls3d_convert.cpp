/// \file pcl_ls3d_convert.cpp
/// \brief Converts point clouds between LAS, LAZ, PCD, PLY and ASCII XYZ in local coordinates with
///        the georeferenced origin restored on output; splits by flight strip, filters by class
///        and crops to a box (-bounds; a COPC input decodes only the octree nodes it meets).
///        LAS/LAZ to LAS/LAZ without a layout change is done record by record, losslessly.

#include "tool_options.h"
#include "tool_output.h"

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/las_io.h>
#include <pcl_ls3d/io/las_records.h>
#include <pcl_ls3d/io/las_rewrite.h>
#include <pcl_ls3d/io/strip_tools.h>
#include <pcl_ls3d/maps/coordinate_reference.h>

#include <pcl/common/io.h>
#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl::console;
namespace fs = std::filesystem;
using Cloud = pcl::PointCloud<pcl_ls3d::PointLiDAR>;

namespace {

void
printHelp(const char* name)
{
  print_error("Syntax is: %s input.{las,laz,copc.laz,pcd,ply,xyz,txt,csv} "
              "output.{las,laz,pcd,ply,xyz,txt} <options>\n"
              "       or: %s input.ext -split_strips DIR <options>\n",
              name, name);
  print_info("  where options are:\n");
  print_info("    -bounds xmin,ymin,xmax,ymax[,zmin,zmax] : keep only the points in this box (file\n"
             "                         coordinates, faces included); a COPC input decodes only\n"
             "                         the octree nodes the box meets\n");
  print_info("    -level N           : with -bounds on a COPC input: octree levels 0..N only (a\n"
             "                         thinned, evenly spread subset)\n");
  print_info("    -split_strips DIR  : write one file per point-source id (flight strip) into DIR,\n"
             "                         named <input stem>_psid<ID>.<ext>\n");
  print_info("    -format EXT        : output format for -split_strips (las laz pcd ply xyz; default:\n"
             "                         input's)\n");
  print_info("    -classes C1,C2,... : keep only these classification codes\n");
  print_info("    -origin x,y,z      : local origin to use instead of the automatic one\n");
  print_info("    -columns x,y,z,... : column names of an ASCII XYZ input (x y z intensity\n"
             "                         classification point_source_id gps_time return_number\n"
             "                         number_of_returns, _ to skip)\n");
  print_info("    -las_format N      : LAS output point format 0-10 (default: input's, else 3)\n");
  print_info("    -las_version 1.N   : LAS output version 1.0-1.4 (default: input's, else 1.2)\n");
  print_info("    -las_scale S       : LAS output quantum (default: input's, else 0.001)\n");
  print_info("    -xyz_decimals N    : XYZ output: x y z with N fixed decimals (0-17; default:\n"
             "                         full precision, the shortest text that reads back exactly)\n");
  print_info("    -ascii             : write PCD/PLY in ASCII instead of binary\n");
  print_info("    -overwrite         : replace existing output files (never an input)\n");
  print_info("    -h                 : this help\n");
  print_info("LAS or LAZ (COPC too) into .las or .laz, without -las_format, -las_version or\n"
             "-las_scale: record by record, losslessly: every point record byte, the header, the\n"
             "VLRs and EVLRs are kept; the LASzip VLR is added or removed (a COPC input's octree\n"
             "VLR and hierarchy EVLR are dropped: the output is no COPC file). -classes and -bounds\n"
             "select records; the header's counts and bounds follow.\n");
  print_info("Coordinates are shifted to a local origin on reading (double precision) and restored\n"
             "on writing; the origin used is printed. A PCD recording its origin in a\n"
             "'# pcl_ls3d origin' header line (pcl_ls3d_segment's SEGMENTS.pcd) is read with it.\n"
             "LAS and XYZ outputs hold file coordinates; PCD and PLY hold them as FLOAT64 when the\n"
             "origin is not zero (as from a georeferenced LAS), else FLOAT32. The input's CRS goes\n"
             "with the points: a PCD or PLY output records it ('# pcl_ls3d crs' / 'comment\n"
             "pcl_ls3d crs' header line, read by every pcl_ls3d tool), and a PCD or PLY that\n"
             "records one gives a LAS output that CRS (LAS 1.4, WKT); XYZ outputs have no place\n"
             "for it.\n");
}

/// Rejects options this tool does not know (pcl::console silently ignores them).
bool
checkOptions(int argc, char** argv, std::vector<std::string>& positional)
{
  const std::set<std::string> with_value = {"-split_strips", "-format",     "-classes",     "-origin",
                                            "-columns",      "-las_format", "-las_version", "-las_scale",
                                            "-xyz_decimals", "-bounds",     "-level"};
  std::string why;
  if (!pcl_ls3d::tools::splitArguments(argc, argv, 1, with_value, {"-ascii", "-overwrite"}, positional,
                                       why)) {
    print_error("%s\n", why.c_str());
    return false;
  }
  return true;
}

bool
save(const std::string& path, const Cloud& cloud, const pcl_ls3d::io::CloudInfo& info,
     const pcl_ls3d::io::SaveOptions& options)
{
  TicToc tt;
  tt.tic();
  std::string error;
  if (!pcl_ls3d::io::saveCloud(path, cloud, info.origin, error, options)) {
    print_error("Cannot write %s\n", error.c_str());
    return false;
  }
  print_info("Wrote ");
  print_value("%s", path.c_str());
  print_info(" (");
  print_value("%zu", cloud.size());
  print_info(" points) in ");
  print_value("%g", tt.toc());
  print_info(" ms\n");
  return true;
}

/// Output settings given on the command line, parsed strictly before anything is read; -1 / 0
/// mean "not given" (the input's LAS layout, full XYZ precision).
struct OutputOverrides
{
  int las_format = -1, las_minor = -1, xyz_decimals = -1;
  double las_scale = 0.0;
};

bool
parseOverrides(int argc, char** argv, OutputOverrides& o, std::string& why)
{
  using pcl_ls3d::tools::integerOption;
  if (!integerOption(argc, argv, "-las_format", o.las_format, why, 0, 10) ||
      !integerOption(argc, argv, "-xyz_decimals", o.xyz_decimals, why, 0, 17) ||
      !pcl_ls3d::tools::numberOption(argc, argv, "-las_scale", o.las_scale, why, 1e-12))
    return false;
  const char* version = pcl_ls3d::tools::optionValue(argc, argv, "-las_version");
  if (version) {
    const std::string v = version;
    if (v.size() != 3 || v.compare(0, 2, "1.") != 0 || v[2] < '0' || v[2] > '4') {
      why = "-las_version must be 1.0-1.4, got '" + v + "'";
      return false;
    }
    o.las_minor = v[2] - '0';
  }
  return true;
}

/// LAS output keeps the input's LAS layout unless told otherwise.
pcl_ls3d::io::SaveOptions
saveOptions(const Cloud& cloud, const pcl_ls3d::io::CloudInfo& info, const OutputOverrides& o)
{
  pcl_ls3d::io::SaveOptions s;
  if (info.format == "las") {
    s.las_point_format = info.las.point_format;
    s.las_minor_version = info.las.version_minor;
    s.las_scale = info.las.scale;
    s.las_vlrs = info.las.vlrs;
    s.las_adjusted_standard_gps_time = info.las.global_encoding & 1;
  } else {
    for (const auto& p : cloud)
      if (p.classification > 31 || p.return_number > 7 || p.number_of_returns > 7) {
        s.las_point_format = 6;  // formats 0-5 cannot hold these values
        s.las_minor_version = 4;
        break;
      }
  }
  // The CRS goes with the points: a LAS's into a PCD or PLY header, theirs into a LAS (LAS 1.4,
  // WKT).
  pcl_ls3d::maps::recordCrs(pcl_ls3d::maps::crsOfFile(info), s);
  if (o.las_format >= 0) {
    s.las_point_format = static_cast<std::uint8_t>(o.las_format);
    if (o.las_format >= 6)
      s.las_minor_version = 4;
  }
  if (o.las_minor >= 0)
    s.las_minor_version = static_cast<std::uint8_t>(o.las_minor);
  if (o.las_scale > 0.0)
    s.las_scale = Eigen::Vector3d::Constant(o.las_scale);
  s.xyz_decimals = o.xyz_decimals;
  return s;
}

/// A SEGMENTS.pcd of MRG or pcl_rg names no classes: the reader leaves its segment ids out of
/// the classification, which stays 0. Said, so that nobody looks for classes in the output.
void
warnNoClasses(const std::string& input, const pcl_ls3d::io::CloudInfo& info)
{
  if (!info.segments_file || info.hasField("classification"))
    return;
  print_warn("%s holds segment ids, not object classes (-mode mrg or pcl_rg): the "
             "classification is left 0 (never classified)\n",
             input.c_str());
}

/// Everything the command line asks for, checked before the input is read (which can take long).
struct Options
{
  std::vector<std::string> files;  ///< input, and the output unless splitting
  std::string split_dir, format, classes_text;
  std::set<std::uint8_t> classes;
  pcl_ls3d::io::LoadOptions load;
  OutputOverrides overrides;
  bool overwrite = false, ascii = false;
};

bool
parseOptions(int argc, char** argv, Options& o, std::string& why)
{
  std::string origin_text;
  parse_argument(argc, argv, "-split_strips", o.split_dir);
  parse_argument(argc, argv, "-format", o.format);
  parse_argument(argc, argv, "-classes", o.classes_text);
  parse_argument(argc, argv, "-origin", origin_text);
  parse_argument(argc, argv, "-columns", o.load.xyz_columns);
  o.overwrite = find_switch(argc, argv, "-overwrite");
  o.ascii = find_switch(argc, argv, "-ascii");
  const bool splitting = !o.split_dir.empty();
  if (o.files.size() != (splitting ? 1u : 2u))
    return (why = std::string("Expected ") +
                  (splitting ? "one input file with -split_strips" : "an input and an output file") +
                  ", got " + std::to_string(o.files.size()) + " file names (see -h)."),
           false;
  std::vector<double> values;
  if (!origin_text.empty()) {
    if (!pcl_ls3d::tools::parseNumberList(origin_text, values) || values.size() != 3)
      return (why = "-origin needs three finite numbers x,y,z, got '" + origin_text + "'."), false;
    o.load.use_origin = true;
    o.load.origin = Eigen::Vector3d(values[0], values[1], values[2]);
  }
  if (!o.classes_text.empty() && !pcl_ls3d::tools::parseClassList("-classes", o.classes_text, o.classes, why))
    return false;
  if (!parseOverrides(argc, argv, o.overrides, why) ||
      !pcl_ls3d::tools::regionOptions(argc, argv, o.load.region, why))
    return false;
  const std::string& input = o.files[0];
  if (splitting && o.format.empty())
    o.format = pcl_ls3d::io::fileExtension(input);
  if (splitting && o.format != "las" && o.format != "laz" && o.format != "pcd" && o.format != "ply" &&
      o.format != "xyz" && o.format != "txt")
    return (why = "-format must be las, laz, pcd, ply, xyz or txt, got '" + o.format + "'."), false;
  if (!splitting && pcl_ls3d::io::isSameFile(input, o.files[1]))
    return (why = "Output " + o.files[1] + " is the input file; refusing to overwrite it."), false;
  return splitting ? pcl_ls3d::tools::checkOutputFolder(o.split_dir, why)
                   : pcl_ls3d::tools::checkOutputFile(o.files[1], {input}, o.overwrite, why, true);
}

/// Loads the input and says what came in and in which frame.
bool
loadInput(const Options& o, Cloud::Ptr& cloud, pcl_ls3d::io::CloudInfo& info, std::string& why)
{
  const std::string& input = o.files[0];
  TicToc tt;
  tt.tic();
  cloud.reset(new Cloud);
  if (!pcl_ls3d::io::loadCloud(input, *cloud, info, why, o.load))
    return (why = "Cannot load " + why), false;
  warnNoClasses(input, info);
  print_info("Loaded ");
  print_value("%s", input.c_str());
  print_info(" (%s, ", info.format.c_str());
  print_value("%zu", info.points_loaded);
  print_info(" points");
  if (info.points_dropped_nonfinite)
    print_info(", %zu NaN/inf dropped", info.points_dropped_nonfinite);
  print_info(") in ");
  print_value("%g", tt.toc());
  print_info(" ms\n");
  if (info.region.copc)
    print_info("Decoded %zu of %zu COPC nodes (%llu points) for -bounds\n", info.region.nodes_read,
               info.region.nodes, static_cast<unsigned long long>(info.region.points_decoded));
  if (info.xyz_unmapped_columns)
    print_info("Note: %zu column(s) of the XYZ input are not used (name them with -columns).\n",
               info.xyz_unmapped_columns);
  print_info("Local origin (%s): ", o.load.use_origin      ? "forced"
                                    : info.has_file_origin ? "recorded in the file"
                                                           : "auto");
  print_value("%.3f %.3f %.3f\n", info.origin[0], info.origin[1], info.origin[2]);
  return true;
}

/// -classes: keeps the points of those classes; false when none is left.
bool
keepClasses(const Options& o, Cloud::Ptr& cloud, std::string& why)
{
  if (o.classes.empty())
    return true;
  const pcl::Indices kept = pcl_ls3d::io::filterByClassification(*cloud, o.classes, true);
  Cloud::Ptr filtered(new Cloud);
  pcl::copyPointCloud(*cloud, kept, *filtered);
  print_info("Kept %zu of %zu points in classes %s\n", filtered->size(), cloud->size(),
             o.classes_text.c_str());
  if (filtered->empty())
    return (why = "No point of " + o.files[0] + " is in classes " + o.classes_text + "."), false;
  cloud = filtered;
  return true;
}

/// -split_strips DIR: one file per point-source id.
bool
writeStrips(const Options& o, const Cloud& cloud, const pcl_ls3d::io::CloudInfo& info,
            const pcl_ls3d::io::SaveOptions& save_options, std::string& why)
{
  std::error_code ec;
  fs::create_directories(o.split_dir, ec);
  if (!fs::is_directory(o.split_dir, ec))
    return (why = "Cannot create the output directory " + o.split_dir + "."), false;
  const auto strips = pcl_ls3d::io::splitByPointSource(cloud);
  print_info("Splitting into %zu strips\n", strips.size());
  const std::string stem = fs::path(o.files[0]).stem().string();
  for (const auto& [id, indices] : strips) {
    const std::string path =
        (fs::path(o.split_dir) / (stem + "_psid" + std::to_string(id) + "." + o.format)).string();
    if (pcl_ls3d::io::isSameFile(o.files[0], path))
      return (why = "Output " + path + " is the input file; refusing to overwrite it."), false;
    Cloud strip;
    pcl::copyPointCloud(cloud, indices, strip);
    if (!save(path, strip, info, save_options))
      return false;  // save() said why
  }
  return true;
}

/// LAS or LAZ in, .las or .laz out, no layout change asked for: the records themselves are
/// converted (lossless), not a cloud of the fields pcl_ls3d keeps.
bool
recordConversion(const Options& o)
{
  const OutputOverrides& v = o.overrides;
  if (!o.split_dir.empty() || v.las_format >= 0 || v.las_minor >= 0 || v.las_scale > 0.0)
    return false;
  const std::string out = pcl_ls3d::io::fileExtension(o.files[1]);
  if (out != "las" && out != "laz")
    return false;
  std::ifstream in(o.files[0], std::ios::binary);
  char signature[4] = {};
  return in.read(signature, 4) && std::string(signature, 4) == "LASF";
}

bool
writeBytes(const std::string& path, const std::vector<std::uint8_t>& bytes, std::string& why)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out ||
      !out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())) ||
      !out.flush())
    return (why = "Cannot write " + path), false;
  return true;
}

/// The whole file, compressed or decompressed as the output's name says: header, VLRs, EVLRs and
/// every record byte kept.
bool
convertWholeFile(const Options& o, std::string& why)
{
  std::ifstream in(o.files[0], std::ios::binary);
  const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
  pcl_ls3d::io::LasHeaderInfo h;
  if (!pcl_ls3d::io::readLasHeader(bytes.data(), bytes.size(), h, why))
    return (why = "Cannot load " + o.files[0] + ": " + why), false;
  const bool to_laz = pcl_ls3d::io::fileExtension(o.files[1]) == "laz";
  std::vector<std::uint8_t> las, out;
  const std::vector<std::uint8_t>* plain = &bytes;
  if (h.laz.compressed) {
    if (!pcl_ls3d::io::decompressLaz(bytes.data(), bytes.size(), las, why))
      return (why = "Cannot load " + o.files[0] + ": " + why), false;
    plain = &las;
  }
  if (to_laz && !pcl_ls3d::io::compressLas(plain->data(), plain->size(), out, why))
    return (why = "Cannot write " + o.files[1] + " as LAZ: " + why), false;
  if (!writeBytes(o.files[1], to_laz ? out : *plain, why))
    return false;
  print_info("Wrote ");
  print_value("%s", o.files[1].c_str());
  print_info(" (%s, ", to_laz ? "LAZ" : "LAS");
  print_value("%llu", static_cast<unsigned long long>(h.point_count));
  print_info(" points): every record byte, the header, VLRs and EVLRs kept\n");
  return true;
}

/// -bounds and -classes on records: the records selected, written by io::rewriteLas (LAS or LAZ
/// by the output's name) with the counts and bounds of what is kept.
bool
convertSelectedRecords(const Options& o, std::string& why)
{
  pcl_ls3d::io::LasRecordFile file;
  const pcl_ls3d::io::Region* region = o.load.region ? &*o.load.region : nullptr;
  if (!file.open(o.files[0], why, region))
    return (why = "Cannot load " + why), false;
  const pcl_ls3d::io::RegionInfo& read = file.regionInfo();
  if (read.copc)
    print_info("Decoded %zu of %zu COPC nodes (%llu points)\n", read.nodes_read, read.nodes,
               static_cast<unsigned long long>(read.points_decoded));
  std::vector<std::size_t> selection;
  for (std::size_t i = 0; i < file.size(); ++i)
    if (o.classes.empty() || o.classes.count(file.classification(i)))
      selection.push_back(i);
  if (selection.empty())
    return (why = "No point of " + o.files[0] + " is inside -bounds and in -classes."), false;
  pcl_ls3d::io::LasRewriteSummary summary;
  if (!pcl_ls3d::io::rewriteLas(file, o.classes.empty() ? nullptr : &selection, nullptr, o.files[1], summary,
                                why, o.overwrite))
    return (why = "Cannot write " + why), false;
  print_info("Wrote ");
  print_value("%s", o.files[1].c_str());
  print_info(" (");
  print_value("%zu", summary.points);
  print_info(" points): their record bytes, the header, VLRs and EVLRs kept\n");
  return true;
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
  Options o;
  if (!checkOptions(argc, argv, o.files))
    return 1;
  Cloud::Ptr cloud;
  pcl_ls3d::io::CloudInfo info;
  std::string why;
  if (!parseOptions(argc, argv, o, why)) {
    print_error("%s\n", why.c_str());
    return 1;
  }
  if (recordConversion(o)) {
    const bool whole = o.classes.empty() && !o.load.region;
    if (!(whole ? convertWholeFile(o, why) : convertSelectedRecords(o, why))) {
      print_error("%s\n", why.c_str());
      return 1;
    }
    return 0;
  }
  if (!loadInput(o, cloud, info, why) || !keepClasses(o, cloud, why)) {
    print_error("%s\n", why.c_str());
    return 1;
  }
  pcl_ls3d::io::SaveOptions save_options = saveOptions(*cloud, info, o.overrides);
  save_options.overwrite = o.overwrite;
  save_options.binary = !o.ascii;
  if (o.split_dir.empty())
    return save(o.files[1], *cloud, info, save_options) ? 0 : 1;
  why.clear();  // save() prints its own reason
  if (!writeStrips(o, *cloud, info, save_options, why)) {
    if (!why.empty())
      print_error("%s\n", why.c_str());
    return 1;
  }
  return 0;
}
