/// \file pcl_ls3d_convert.cpp
/// \brief Converts point clouds between LAS, PCD, PLY and ASCII XYZ in local coordinates with the
///        georeferenced origin restored on output; splits by flight strip and filters by class.

#include "tool_arguments.h"
#include "tool_output.h"

#include <pcl_ls3d/evaluation/segments_file.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/io/las_io.h>
#include <pcl_ls3d/io/strip_tools.h>
#include <pcl_ls3d/maps/coordinate_reference.h>

#include <pcl/common/io.h>
#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
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
  print_error("Syntax is: %s input.{las,pcd,ply,xyz,txt,csv} output.{las,pcd,ply,xyz,txt} <options>\n"
              "       or: %s input.ext -split_strips DIR <options>\n", name, name);
  print_info("  where options are:\n");
  print_info("    -split_strips DIR  : write one file per point-source id (flight strip) into DIR,\n"
             "                         named <input stem>_psid<ID>.<ext>\n");
  print_info("    -format EXT        : output format for -split_strips (las pcd ply xyz; default: input's)\n");
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
  print_info("Coordinates are shifted to a local origin on reading (double precision) and restored\n"
             "on writing; the origin used is printed. A PCD recording its origin in a\n"
             "'# pcl_ls3d origin' header line (pcl_ls3d_segment's SEGMENTS.pcd) is read with it.\n"
             "LAS and XYZ outputs hold file coordinates; PCD and PLY hold them as FLOAT64 when the\n"
             "origin is not zero (as from a georeferenced LAS), else FLOAT32. A PCD that records\n"
             "its CRS ('# pcl_ls3d crs' header line) gives a LAS output that CRS (LAS 1.4, WKT).\n");
}

/// Rejects options this tool does not know (pcl::console silently ignores them).
bool
checkOptions(int argc, char** argv, std::vector<std::string>& positional)
{
  const std::set<std::string> with_value = {"-split_strips", "-format", "-classes", "-origin",
                                            "-columns", "-las_format", "-las_version", "-las_scale",
                                            "-xyz_decimals"};
  std::string why;
  if (!pcl_ls3d::tools::splitArguments(argc, argv, 1, with_value, {"-ascii", "-overwrite"},
                                       positional, why)) {
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
  }
  else {
    for (const auto& p : cloud)
      if (p.classification > 31 || p.return_number > 7 || p.number_of_returns > 7) {
        s.las_point_format = 6;  // formats 0-5 cannot hold these values
        s.las_minor_version = 4;
        break;
      }
    // A PCD that records its CRS (SEGMENTS.pcd) gives the LAS its CRS: LAS 1.4, WKT VLR.
    if (!info.file_crs_wkt.empty()) {
      s.las_vlrs = {pcl_ls3d::maps::wktVlr(info.file_crs_wkt)};
      s.las_minor_version = 4;
    }
  }
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

/// A SEGMENTS.pcd of MRG or pcl_rg names no classes: its label holds segment ids, which the
/// reader takes for the classification (clamped to a byte). They are not classes: left 0.
void
dropSegmentIds(const std::string& input, const pcl_ls3d::io::CloudInfo& info, Cloud& cloud)
{
  if (info.format != "pcd" || !pcl_ls3d::evaluation::isSegmentsFile(input) ||
      std::find(info.fields.begin(), info.fields.end(), "classification") != info.fields.end())
    return;
  for (auto& p : cloud)
    p.classification = 0;
  print_warn("%s holds segment ids, not object classes (-mode mrg or pcl_rg): the "
             "classification is left 0 (never classified)\n", input.c_str());
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
  std::vector<std::string> files;
  if (!checkOptions(argc, argv, files))
    return 1;
  std::string split_dir, format, classes_text, origin_text, columns;
  parse_argument(argc, argv, "-split_strips", split_dir);
  parse_argument(argc, argv, "-format", format);
  parse_argument(argc, argv, "-classes", classes_text);
  parse_argument(argc, argv, "-origin", origin_text);
  parse_argument(argc, argv, "-columns", columns);
  const bool splitting = !split_dir.empty();
  if (files.size() != (splitting ? 1u : 2u)) {
    print_error("Expected %s, got %zu file names (see -h).\n",
                splitting ? "one input file with -split_strips" : "an input and an output file",
                files.size());
    return 1;
  }
  const std::string input = files[0];

  pcl_ls3d::io::LoadOptions load;
  load.xyz_columns = columns;
  std::vector<double> values;
  if (!origin_text.empty()) {
    if (!pcl_ls3d::tools::parseNumberList(origin_text, values) || values.size() != 3) {
      print_error("-origin needs three finite numbers x,y,z, got '%s'.\n", origin_text.c_str());
      return 1;
    }
    load.use_origin = true;
    load.origin = Eigen::Vector3d(values[0], values[1], values[2]);
  }
  std::set<std::uint8_t> classes;
  std::string why;
  if (!classes_text.empty() && !pcl_ls3d::tools::parseClassList("-classes", classes_text, classes, why)) {
    print_error("%s\n", why.c_str());
    return 1;
  }

  OutputOverrides overrides;
  if (!parseOverrides(argc, argv, overrides, why)) {
    print_error("%s\n", why.c_str());
    return 1;
  }
  if (splitting && format.empty())
    format = pcl_ls3d::io::fileExtension(input);
  if (splitting && format != "las" && format != "pcd" && format != "ply" && format != "xyz" &&
      format != "txt") {
    print_error("-format must be las, pcd, ply, xyz or txt, got '%s'.\n", format.c_str());
    return 1;
  }

  // Outputs are checked before the input is read (which can take long).
  const bool overwrite = find_switch(argc, argv, "-overwrite");
  if (!splitting && pcl_ls3d::io::isSameFile(input, files[1])) {
    print_error("Output %s is the input file; refusing to overwrite it.\n", files[1].c_str());
    return 1;
  }
  if (splitting ? !pcl_ls3d::tools::checkOutputFolder(split_dir, why)
                : !pcl_ls3d::tools::checkOutputFile(files[1], {input}, overwrite, why, true)) {
    print_error("%s\n", why.c_str());
    return 1;
  }

  // Load.
  TicToc tt;
  tt.tic();
  Cloud::Ptr cloud(new Cloud);
  pcl_ls3d::io::CloudInfo info;
  std::string error;
  if (!pcl_ls3d::io::loadCloud(input, *cloud, info, error, load)) {
    print_error("Cannot load %s\n", error.c_str());
    return 1;
  }
  dropSegmentIds(input, info, *cloud);
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
  if (info.xyz_unmapped_columns)
    print_info("Note: %zu column(s) of the XYZ input are not used (name them with -columns).\n",
               info.xyz_unmapped_columns);
  print_info("Local origin (%s): ", load.use_origin            ? "forced"
                                    : info.has_file_origin ? "recorded in the file"
                                                                 : "auto");
  print_value("%.3f %.3f %.3f\n", info.origin[0], info.origin[1], info.origin[2]);

  if (!classes.empty()) {
    const pcl::Indices kept = pcl_ls3d::io::filterByClassification(*cloud, classes, true);
    Cloud::Ptr filtered(new Cloud);
    pcl::copyPointCloud(*cloud, kept, *filtered);
    print_info("Kept %zu of %zu points in classes %s\n", filtered->size(), cloud->size(),
               classes_text.c_str());
    if (filtered->empty()) {
      print_error("No point of %s is in classes %s.\n", input.c_str(), classes_text.c_str());
      return 1;
    }
    cloud = filtered;
  }

  pcl_ls3d::io::SaveOptions save_options = saveOptions(*cloud, info, overrides);
  save_options.overwrite = overwrite;
  save_options.binary = !find_switch(argc, argv, "-ascii");

  if (!splitting) {
    return save(files[1], *cloud, info, save_options) ? 0 : 1;
  }

  // -split_strips DIR: one file per point-source id.
  std::error_code ec;
  fs::create_directories(split_dir, ec);
  if (!fs::is_directory(split_dir, ec)) {
    print_error("Cannot create the output directory %s.\n", split_dir.c_str());
    return 1;
  }
  const auto strips = pcl_ls3d::io::splitByPointSource(*cloud);
  print_info("Splitting into %zu strips\n", strips.size());
  const std::string stem = fs::path(input).stem().string();
  for (const auto& [id, indices] : strips) {
    const std::string path =
        (fs::path(split_dir) / (stem + "_psid" + std::to_string(id) + "." + format)).string();
    if (pcl_ls3d::io::isSameFile(input, path)) {
      print_error("Output %s is the input file; refusing to overwrite it.\n", path.c_str());
      return 1;
    }
    Cloud strip;
    pcl::copyPointCloud(*cloud, indices, strip);
    if (!save(path, strip, info, save_options))
      return 1;
  }
  return 0;
}
