/// \file pcl_ls3d_synth.cpp
/// \brief Writes synthetic clouds with known truth: a registration pair, a labelled scene,
///        a block of flight strips, or Li et al.'s deformation surface, plus truth.json.

#include "tool_options.h"
#include "tool_output.h"

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/synth/truth_json.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl::console;
namespace fs = std::filesystem;
namespace synth = pcl_ls3d::synth;
using Cloud = pcl::PointCloud<pcl_ls3d::PointLiDAR>;

namespace {

// Options per subcommand (value options; switches listed separately).
const std::set<std::string> kCommon = {"-seed", "-o", "-format", "-noise"};
const std::map<std::string, std::set<std::string>> kValues = {
    {"pair",
     {"-size", "-source_density", "-target_density", "-overlap", "-transform", "-origin", "-relief",
      "-wavelength", "-buildings_per_ha"}},
    {"scene",
     {"-size", "-density", "-origin", "-relief", "-wavelength", "-buildings_per_ha", "-trees", "-shrubs",
      "-cars", "-car_class", "-towers", "-wires"}},
    {"strips",
     {"-strips", "-heading", "-length", "-swath", "-side_overlap", "-density", "-pattern", "-shift_sigma",
      "-angle_sigma", "-scale_sigma", "-origin", "-relief", "-wavelength", "-buildings_per_ha", "-speed"}},
    {"li", {"-grid", "-spacing", "-relief", "-wavelength", "-percent", "-c", "-position", "-transform"}}};
const std::map<std::string, std::set<std::string>> kSwitches = {
    {"pair", {"-no_buildings"}},
    {"scene", {"-no_buildings", "-no_power_line"}},
    {"strips", {"-no_buildings", "-no_fix_first", "-split"}},
    {"li", {"-noise_on_reference"}}};

void
printHelp(const char* name)
{
  print_error("Syntax is: %s <pair|scene|strips|li> -o OUTDIR <options>\n", name);
  print_info(
      "  pair   : OUTDIR/source.<fmt>, OUTDIR/target.<fmt>, OUTDIR/truth.json (truth maps source\n"
      "           into target, in written coordinates)\n"
      "  scene  : OUTDIR/scene.<fmt> (ASPRS classes 2,3,4,5,6,14,15 and cars), OUTDIR/truth.json\n"
      "  strips : OUTDIR/strips.<fmt> (all strips; -split adds OUTDIR/strip_<id>.<fmt>), truth.json\n"
      "  li     : OUTDIR/reference.<fmt>, OUTDIR/mate.<fmt>, OUTDIR/truth.json (Li et al. 2001)\n"
      "  common options:\n"
      "    -seed N            : random seed (default 1)\n"
      "    -o DIR             : output folder (created if missing)\n"
      "    -format F          : pcd | ply | las | laz | xyz (default pcd)\n"
      "    -noise S           : isotropic noise sigma per axis (pair/strips 0.05 m, scene 0.03 m,\n"
      "                         li 20 units)\n"
      "    -overwrite         : replace existing output files\n"
      "    -h                 : this help\n"
      "  pair:   -size X,Y (300,300 m) -source_density D (1/m2) -target_density D (4/m2)\n"
      "          -overlap F (0.7) -transform tx,ty,tz,phi,omega,kappa,m (rad; default\n"
      "          0.5,-0.3,0.2,0.002,-0.0015,0.003,1.0002) -origin x,y,z (0,0,0) -relief R (10)\n"
      "          -wavelength W (60) -buildings_per_ha N (2) -no_buildings\n"
      "  scene:  -size X,Y (200,200) -density D (8 pulses/m2) -trees N -shrubs N -cars N (per ha:\n"
      "          30,30,10) -car_class C (64) -towers N (3) -wires N (3) -buildings_per_ha N (5)\n"
      "          -relief R (6) -wavelength W (80) -origin x,y,z -no_buildings -no_power_line\n"
      "  strips: -strips N (3) -heading RAD (0) -length L (600) -swath W (300) -side_overlap F\n"
      "          (0.3) -density D (4) -pattern zigzag|parallel -speed V (60 m/s) -shift_sigma S\n"
      "          (0.15 m) -angle_sigma A (3e-4 rad) -scale_sigma S (5e-5) -origin x,y,z\n"
      "          -relief R -wavelength W -buildings_per_ha N -no_buildings -no_fix_first -split\n"
      "  li:     -grid N (50) -spacing S (100) -relief R (5000) -wavelength W (3000) -percent P\n"
      "          (9) -c C (10: deformation N(c*sigma, sigma)) -position NAME (upper_right; also\n"
      "          upper_left upper left middle right lower_left lower lower_right)\n"
      "          -transform tx,ty,tz,phi,omega,kappa[,m] (default Li Table 4: 500,500,500 and 5 deg each)\n"
      "          -noise_on_reference\n");
}

/// Rejects unknown options and stray words; pcl::console would silently ignore them.
bool
checkOptions(int argc, char** argv, const std::string& cmd)
{
  std::set<std::string> values = kCommon, switches = {"-overwrite"};
  values.insert(kValues.at(cmd).begin(), kValues.at(cmd).end());
  switches.insert(kSwitches.at(cmd).begin(), kSwitches.at(cmd).end());
  std::vector<std::string> stray;
  std::string why;
  if (!pcl_ls3d::tools::splitArguments(argc, argv, 2, values, switches, stray, why)) {
    print_error("%s: %s\n", cmd.c_str(), why.c_str());
    return false;
  }
  if (!stray.empty()) {
    print_error("Unexpected argument '%s' for '%s' (see -h).\n", stray[0].c_str(), cmd.c_str());
    return false;
  }
  return true;
}

/// Reads option `name` (if given) as `count` numbers (count 0: any count). Sets ok = false and
/// prints the error on a malformed value.
std::vector<double>
numbers(int argc, char** argv, const char* name, std::size_t count, bool& ok)
{
  std::string text;
  std::vector<double> v;
  if (parse_argument(argc, argv, name, text) < 0)
    return v;
  if (!pcl_ls3d::tools::parseNumberList(text, v) || (count && v.size() != count)) {
    print_error("%s needs %zu finite comma-separated number(s), got '%s'.\n", name, count, text.c_str());
    ok = false;
    v.clear();
  }
  return v;
}

template <typename T>
void
setIf(int argc, char** argv, const char* name, T& target, bool& ok)
{
  const auto v = numbers(argc, argv, name, 1, ok);
  if (!v.empty())
    target = static_cast<T>(v[0]);
}

/// Unsigned integer option in [lo, hi].
template <typename T>
void
setInt(int argc, char** argv, const char* name, T& target, double lo, double hi, bool& ok)
{
  const auto v = numbers(argc, argv, name, 1, ok);
  if (v.empty())
    return;
  if (v[0] != std::floor(v[0]) || v[0] < lo || v[0] > hi) {
    print_error("%s must be an integer in [%g, %g], got %g.\n", name, lo, hi, v[0]);
    ok = false;
    return;
  }
  target = static_cast<T>(v[0]);
}

void
setOrigin(int argc, char** argv, Eigen::Vector3d& origin, bool& ok)
{
  const auto v = numbers(argc, argv, "-origin", 3, ok);
  if (!v.empty())
    origin = Eigen::Vector3d(v[0], v[1], v[2]);
}

void
setSize(int argc, char** argv, double& x, double& y, bool& ok)
{
  const auto v = numbers(argc, argv, "-size", 2, ok);
  if (!v.empty()) {
    x = v[0];
    y = v[1];
  }
}

/// -transform with 6 (m = 1) or 7 values.
void
setTransform(int argc, char** argv, pcl_ls3d::SimilarityTransform& T, bool allow7, bool& ok)
{
  const auto v = numbers(argc, argv, "-transform", 0, ok);
  if (v.empty())
    return;
  if (v.size() != 7 && !(v.size() == 6)) {
    print_error("-transform needs tx,ty,tz,phi,omega,kappa%s (got %zu values).\n", allow7 ? "[,m]" : "",
                v.size());
    ok = false;
    return;
  }
  if (v.size() == 7 && !allow7) {
    print_error("-transform takes 6 values here (rigid).\n");
    ok = false;
    return;
  }
  pcl_ls3d::Vector7d p;
  p << v[0], v[1], v[2], v[3], v[4], v[5], v.size() == 7 ? v[6] : 1.0;
  T = pcl_ls3d::SimilarityTransform(p);
}

/// Refuses existing outputs without -overwrite, before anything is generated.
bool
refuseExisting(const std::vector<std::string>& paths, bool overwrite)
{
  for (const auto& p : paths)
    if (!overwrite && fs::exists(p)) {
      print_error("%s exists; use -overwrite to replace it.\n", p.c_str());
      return false;
    }
  return true;
}

struct Output
{
  std::string path;
  const Cloud* cloud;
  Eigen::Vector3d origin;
};

/// Refuses existing files without -overwrite (before anything is written), then writes all.
bool
writeAll(const std::vector<Output>& clouds, const std::string& json_path, const std::string& json,
         bool overwrite, const std::string& format)
{
  std::vector<std::string> paths{json_path};
  for (const auto& o : clouds)
    paths.push_back(o.path);
  if (!refuseExisting(paths, overwrite))
    return false;
  pcl_ls3d::io::SaveOptions opt;
  opt.overwrite = true;  // checked above for all files at once
  for (const auto& o : clouds) {
    TicToc tt;
    tt.tic();
    std::string error;
    if (!pcl_ls3d::io::saveCloud(o.path, *o.cloud, o.origin, error, opt)) {
      print_error("Cannot write %s: %s\n", o.path.c_str(), error.c_str());
      return false;
    }
    print_info("Wrote ");
    print_value("%s", o.path.c_str());
    print_info(" (");
    print_value("%zu", o.cloud->size());
    print_info(" points) in ");
    print_value("%g", tt.toc());
    print_info(" ms\n");
  }
  std::string error;
  if (!synth::writeTextFile(json_path, json, true, error)) {
    print_error("%s\n", error.c_str());
    return false;
  }
  print_info("Wrote ");
  print_value("%s\n", json_path.c_str());
  return true;
}

/// What every subcommand needs: seed, output names, overwrite flag.
struct Context
{
  std::uint32_t seed = 1;
  std::string outdir, format, json_path;
  bool overwrite = false;
  std::string
  file(const std::string& stem) const
  {
    return (fs::path(outdir) / (stem + "." + format)).string();
  }
};

int
runPair(int argc, char** argv, const Context& ctx)
{
  bool ok = true;
  std::string why;
  TicToc tt;
  synth::RegistrationPairSettings s;
  s.seed = ctx.seed;
  setIf(argc, argv, "-noise", s.noise_sigma, ok);
  setSize(argc, argv, s.size_x, s.size_y, ok);
  setIf(argc, argv, "-source_density", s.source_density, ok);
  setIf(argc, argv, "-target_density", s.target_density, ok);
  setIf(argc, argv, "-overlap", s.overlap, ok);
  setIf(argc, argv, "-relief", s.relief, ok);
  setIf(argc, argv, "-wavelength", s.wavelength, ok);
  setIf(argc, argv, "-buildings_per_ha", s.building_settings.per_hectare, ok);
  setTransform(argc, argv, s.truth, true, ok);
  setOrigin(argc, argv, s.origin, ok);
  s.buildings = !find_switch(argc, argv, "-no_buildings");
  if (!ok)
    return 1;
  if (!s.isValid(&why)) {
    print_error("Invalid pair settings: %s.\n", why.c_str());
    return 1;
  }
  if (!refuseExisting({ctx.json_path, ctx.file("source"), ctx.file("target")}, ctx.overwrite))
    return 1;
  tt.tic();
  const auto pair = synth::makeRegistrationPair(s);
  print_info("Generated pair: ");
  print_value("%zu", pair.source->size());
  print_info(" source, ");
  print_value("%zu", pair.target->size());
  print_info(" target points in ");
  print_value("%g", tt.toc());
  print_info(" ms\n");
  return writeAll({{ctx.file("source"), pair.source.get(), pair.origin},
                   {ctx.file("target"), pair.target.get(), pair.origin}},
                  ctx.json_path, synth::truthJson(pair, s), ctx.overwrite, ctx.format)
             ? 0
             : -1;
}

int
runScene(int argc, char** argv, const Context& ctx)
{
  bool ok = true;
  std::string why;
  TicToc tt;
  synth::SceneSettings s;
  s.seed = ctx.seed;
  setIf(argc, argv, "-noise", s.noise_sigma, ok);
  setSize(argc, argv, s.size_x, s.size_y, ok);
  setIf(argc, argv, "-density", s.density, ok);
  setIf(argc, argv, "-relief", s.relief, ok);
  setIf(argc, argv, "-wavelength", s.wavelength, ok);
  setIf(argc, argv, "-buildings_per_ha", s.building_settings.per_hectare, ok);
  setIf(argc, argv, "-trees", s.trees_per_hectare, ok);
  setIf(argc, argv, "-shrubs", s.shrubs_per_hectare, ok);
  setIf(argc, argv, "-cars", s.cars_per_hectare, ok);
  setInt(argc, argv, "-car_class", s.car_class, 0, 255, ok);
  setInt(argc, argv, "-towers", s.towers, 2, 100, ok);
  setInt(argc, argv, "-wires", s.wires, 1, 20, ok);
  setOrigin(argc, argv, s.origin, ok);
  s.buildings = !find_switch(argc, argv, "-no_buildings");
  s.power_line = !find_switch(argc, argv, "-no_power_line");
  if (!ok)
    return 1;
  if (!s.isValid(&why)) {
    print_error("Invalid scene settings: %s.\n", why.c_str());
    return 1;
  }
  if (!refuseExisting({ctx.json_path, ctx.file("scene")}, ctx.overwrite))
    return 1;
  tt.tic();
  const auto scene = synth::makeScene(s);
  print_info("Generated scene: ");
  print_value("%zu", scene.cloud->size());
  print_info(" points, ");
  print_value("%zu", scene.objects.size());
  print_info(" objects in ");
  print_value("%g", tt.toc());
  print_info(" ms\n");
  return writeAll({{ctx.file("scene"), scene.cloud.get(), scene.origin}}, ctx.json_path,
                  synth::truthJson(scene, s), ctx.overwrite, ctx.format)
             ? 0
             : -1;
}

int
runStrips(int argc, char** argv, const Context& ctx)
{
  bool ok = true;
  std::string why;
  TicToc tt;
  synth::StripSettings s;
  s.seed = ctx.seed;
  setIf(argc, argv, "-noise", s.noise_sigma, ok);
  setInt(argc, argv, "-strips", s.num_strips, 1, 1000, ok);
  setIf(argc, argv, "-heading", s.heading, ok);
  setIf(argc, argv, "-length", s.strip_length, ok);
  setIf(argc, argv, "-swath", s.swath_width, ok);
  setIf(argc, argv, "-side_overlap", s.side_overlap, ok);
  setIf(argc, argv, "-density", s.density, ok);
  setIf(argc, argv, "-speed", s.speed, ok);
  setIf(argc, argv, "-shift_sigma", s.shift_sigma, ok);
  setIf(argc, argv, "-angle_sigma", s.angle_sigma, ok);
  setIf(argc, argv, "-scale_sigma", s.scale_sigma, ok);
  setIf(argc, argv, "-relief", s.relief, ok);
  setIf(argc, argv, "-wavelength", s.wavelength, ok);
  setIf(argc, argv, "-buildings_per_ha", s.building_settings.per_hectare, ok);
  setOrigin(argc, argv, s.origin, ok);
  std::string pattern;
  if (parse_argument(argc, argv, "-pattern", pattern) >= 0) {
    if (pattern != "zigzag" && pattern != "parallel") {
      print_error("-pattern must be zigzag or parallel, got '%s'.\n", pattern.c_str());
      return 1;
    }
    s.pattern = pattern == "zigzag" ? synth::ScanPattern::ZIGZAG : synth::ScanPattern::PARALLEL;
  }
  s.buildings = !find_switch(argc, argv, "-no_buildings");
  s.fix_first = !find_switch(argc, argv, "-no_fix_first");
  if (!ok)
    return 1;
  if (!s.isValid(&why)) {
    print_error("Invalid strip settings: %s.\n", why.c_str());
    return 1;
  }
  const bool split = find_switch(argc, argv, "-split");
  std::vector<std::string> planned{ctx.json_path, ctx.file("strips")};
  for (int k = 0; split && k < s.num_strips; ++k)
    planned.push_back(ctx.file("strip_" + std::to_string(s.first_source_id + k)));
  if (!refuseExisting(planned, ctx.overwrite))
    return 1;
  tt.tic();
  const auto block = synth::makeStripBlock(s);
  print_info("Generated ");
  print_value("%zu", block.strips.size());
  print_info(" strips, ");
  print_value("%zu", block.cloud->size());
  print_info(" points in ");
  print_value("%g", tt.toc());
  print_info(" ms\n");
  std::vector<Cloud::Ptr> parts;
  std::vector<Output> outputs{{ctx.file("strips"), block.cloud.get(), block.origin}};
  if (split)
    for (std::size_t k = 0; k < block.strips.size(); ++k) {
      parts.push_back(block.stripCloud(k));
      outputs.push_back({ctx.file("strip_" + std::to_string(block.strips[k].point_source_id)),
                         parts.back().get(), block.origin});
    }
  return writeAll(outputs, ctx.json_path, synth::truthJson(block, s), ctx.overwrite, ctx.format) ? 0 : -1;
}

int
runLi(int argc, char** argv, const Context& ctx)
{
  bool ok = true;
  std::string why;
  TicToc tt;
  synth::LiSurfaceSettings s;
  s.seed = ctx.seed;
  setIf(argc, argv, "-noise", s.noise_sigma, ok);
  setInt(argc, argv, "-grid", s.grid_size, 2, 20000, ok);
  setIf(argc, argv, "-spacing", s.spacing, ok);
  setIf(argc, argv, "-relief", s.relief, ok);
  setIf(argc, argv, "-wavelength", s.wavelength, ok);
  setIf(argc, argv, "-percent", s.deformation_percent, ok);
  setIf(argc, argv, "-c", s.deformation_c, ok);
  setTransform(argc, argv, s.truth, true, ok);
  std::string position;
  if (parse_argument(argc, argv, "-position", position) >= 0 &&
      !synth::parseDeformationPosition(position, s.position)) {
    print_error("Unknown -position '%s' (see -h).\n", position.c_str());
    return 1;
  }
  s.noise_on_reference = find_switch(argc, argv, "-noise_on_reference");
  if (!ok)
    return 1;
  if (!s.isValid(&why)) {
    print_error("Invalid li settings: %s.\n", why.c_str());
    return 1;
  }
  if (!refuseExisting({ctx.json_path, ctx.file("reference"), ctx.file("mate")}, ctx.overwrite))
    return 1;
  tt.tic();
  const auto li = synth::makeLiSurface(s);
  print_info("Generated Li surface: ");
  print_value("%zu", li.reference->size());
  print_info(" nodes, ");
  print_value("%.2f", li.percent);
  print_info(" %% deformed in ");
  print_value("%g", tt.toc());
  print_info(" ms\n");
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  return writeAll(
             {{ctx.file("reference"), li.reference.get(), zero}, {ctx.file("mate"), li.mate.get(), zero}},
             ctx.json_path, synth::truthJson(li, s), ctx.overwrite, ctx.format)
             ? 0
             : -1;
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
  const std::string cmd = argv[1];
  if (!kValues.count(cmd)) {
    print_error("Unknown subcommand '%s': use pair, scene, strips or li (see -h).\n", cmd.c_str());
    return 1;
  }
  if (!checkOptions(argc, argv, cmd))
    return 1;
  std::string outdir, format = "pcd";
  if (parse_argument(argc, argv, "-o", outdir) < 0 || outdir.empty()) {
    print_error("Missing -o OUTDIR (see -h).\n");
    return 1;
  }
  parse_argument(argc, argv, "-format", format);
  if (format != "pcd" && format != "ply" && format != "las" && format != "laz" && format != "xyz") {
    print_error("-format must be pcd, ply, las, laz or xyz, got '%s'.\n", format.c_str());
    return 1;
  }
  const bool overwrite = find_switch(argc, argv, "-overwrite");
  bool ok = true;
  std::uint32_t seed = 1;
  setInt(argc, argv, "-seed", seed, 0, 4294967295.0, ok);
  if (!ok)
    return 1;
  std::error_code ec;
  std::string why;
  if (!pcl_ls3d::tools::checkOutputFolder(outdir, why)) {
    print_error("%s\n", why.c_str());
    return 1;
  }
  fs::create_directories(outdir, ec);
  if (ec || !fs::is_directory(outdir)) {
    print_error("Cannot create output folder %s.\n", outdir.c_str());
    return 1;
  }
  Context ctx;
  ctx.seed = seed;
  ctx.outdir = outdir;
  ctx.format = format;
  ctx.overwrite = overwrite;
  ctx.json_path = (fs::path(outdir) / "truth.json").string();
  if (cmd == "pair")
    return runPair(argc, argv, ctx);
  if (cmd == "scene")
    return runScene(argc, argv, ctx);
  if (cmd == "strips")
    return runStrips(argc, argv, ctx);
  return runLi(argc, argv, ctx);
}
