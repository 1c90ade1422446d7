// pcl_ls3d_strip_adjust: simultaneous block adjustment of airborne LiDAR strips on the LS3D engine
// (Zuo et al. 2012, §3), in one process or as the stages plan / match / solve / apply of a
// cluster run (scripts/slurm/strip_adjust.sbatch).
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/strips/report_output.h>
#include <pcl_ls3d/strips/strip_stages.h>

#include "tool_options.h"
#include "tool_output.h"

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <cstdlib>
#include <filesystem>
#include <limits>
#include <set>
#include <string>
#include <vector>

using namespace pcl::console;
using namespace pcl_ls3d;
namespace fs = std::filesystem;

namespace {

void
printHelp(const char* prog)
{
  print_info(
      "Strip block adjustment: corrects overlapping airborne LiDAR strips into one consistent surface.\n"
      "Every strip gets its own similarity transform (Zuo et al. 2012), all estimated at once from\n"
      "conjugate points between the stable surfaces of every overlap, in both directions.\n\n"
      "Usage: %s INPUT... [options]                    adjust in this process\n"
      "       %s plan INPUT... -work DIR [options]     cluster stages (see "
      "scripts/slurm/strip_adjust.sbatch)\n"
      "       %s match -work DIR -job K | solve -work DIR | apply -work DIR -unit K | counts -work DIR\n\n"
      "  INPUT...               .las (1.0-1.4) .laz .copc.laz .pcd .ply .xyz; one strip per\n"
      "                         file, or see -split\n"
      "  -split psid            one strip per LAS point-source id over all inputs (id 0: no strip,\n"
      "                         written unchanged)\n"
      "  -reference ID[,ID]     fixed reference strips: point-source ids with -split, else file names\n"
      "                         without extension (default: per connected block the strip with the\n"
      "                         largest overlap area)\n"
      "  -soft t,angle,m        soft datum instead: every strip observed at the identity with these\n"
      "                         a-priori sigmas (length, rad, -); no strip fixed\n"
      "  -params 7|6|3|z        per strip: similarity, rigid (default), translation, height only\n"
      "  -rule lnd|lzd|icp      conjugate-point rule (default lnd; icp needs strips already within\n"
      "                         about a point spacing: from metres off it can stop off the truth)\n"
      "  -estimator E           zuo[:K] (default zuo:6), huber[:k], tukey[:c], md, ls\n"
      "  -classes 2,6           stable-surface classes of classified strips (default 2,6)\n"
      "  -spacing S             one observation per S x S cell (default, or 0: 2x the point\n"
      "                         spacing, at most -max_obs per overlap and direction)\n"
      "  -max_obs N             default 60000 (at least 10)\n"
      "  -max_dist D            farthest conjugate point (default 10, data units)\n"
      "  -min_area A            skip overlaps with a smaller common area (default 100 footprint cells)\n"
      "  -min_obs N             match an overlap's direction only with at least N observed points\n"
      "                         (default 100)\n"
      "  -one_way               observe each overlap one way (the first strip's points on the\n"
      "                         second's surface; default: both ways)\n"
      "  -max_iter N            iteration limit (default 30)\n"
      "  -held_out_z Z          with -params 6: a strip's held-out scale is significant beyond Z\n"
      "                         times its sigma (default 5; inf: no test)\n"
      "  -held_out_noise F      ... and makes the result NOT CONFIRMED when it also moves the\n"
      "                         strip's edge by more than F x the strip's own noise (default 1)\n"
      "  -o DIR                 write the corrected strips in the input's format (LAS and LAZ: every\n"
      "                         attribute and VLR kept, only x, y, z and the header bounds change;\n"
      "                         a .copc.laz comes back as .laz); never into a folder holding an input\n"
      "  -keep_files            with -split: write each input whole under its own name\n"
      "                         (default: NAME_psid<ID>.EXT per input and point-source id)\n"
      "  -json REPORT           JSON report\n"
      "  -maps DIR              discrepancy maps before/after per overlap and for the whole block\n"
      "                         (GeoTIFF in the input's CRS + PNG, PDF or SVG), histograms\n"
      "  -map_format F          png (default), pdf or svg: the maps and histograms as .F files\n"
      "                         (pdf and svg: vector graphics for reports)\n"
      "  -bands a,b             tolerance classes of the maps in metres (default 0.10,0.20; without\n"
      "                         a CRS in the input's own unit)\n"
      "  -overwrite             replace existing outputs (never an input)\n"
      "  -q                     quiet: errors only\n"
      "  -h                     this help\n\n"
      "Exit status: 0 converged (or at the iteration limit); 1 bad input or options; 2 no solution\n"
      "(singular, too few observations); 3 UNRELIABLE: corrections larger than the strips' noise that\n"
      "do not reduce the discrepancies on most overlaps, or a held-out scale the overlaps ask for\n"
      "(outputs written, the report says why).\n",
      prog, prog, prog);
}

int
fail(const std::string& message)
{
  print_error("%s\n", message.c_str());
  return 1;
}

const std::set<std::string> kWithValue = {
    "-split",          "-reference", "-soft",     "-params",   "-rule",    "-estimator", "-classes",
    "-spacing",        "-max_obs",   "-max_dist", "-min_area", "-min_obs", "-max_iter",  "-held_out_z",
    "-held_out_noise", "-o",         "-json",     "-maps",     "-bands",   "-work",      "-job",
    "-unit",           "-map_format"};
const std::set<std::string> kSwitches = {"-keep_files", "-overwrite", "-q", "-one_way"};

// Options shared by the single run and the plan stage, parsed into the plan request.
struct Options
{
  std::vector<std::string> inputs;
  strips::PlanFile request;
  std::vector<std::string> references;
  bool overwrite = false, quiet = false;
  std::string work;
  int job = -1, unit = -1;
};

// -held_out_z: a positive number, or inf to switch the test off.
bool
heldOutZOption(int argc, char** argv, double& z, std::string& why)
{
  const char* text = tools::optionValue(argc, argv, "-held_out_z");
  if (text && std::string(text) == "inf") {
    z = std::numeric_limits<double>::infinity();
    return true;
  }
  if (!tools::numberOption(argc, argv, "-held_out_z", z, why, 0.0))
    return false;
  return z > 0.0 || (why = "-held_out_z must be > 0 (inf: no test)").empty();
}

// -split and -reference: which points form the strips, and which strips are fixed.
bool
stripOptions(int argc, char** argv, Options& o, std::string& why)
{
  std::string text;
  if (parse_argument(argc, argv, "-split", text) >= 0) {
    if (text != "psid")
      return (why = "-split takes 'psid'").empty();
    o.request.load.split_by_point_source = true;
  }
  if (parse_argument(argc, argv, "-reference", text) >= 0) {
    std::stringstream ss(text);
    for (std::string id; std::getline(ss, id, ',');)
      o.references.push_back(id);
  }
  return true;
}

// -soft, -params, -rule, -estimator, -classes: the model and how it is observed.
bool
modelOptions(int argc, char** argv, strips::StripAdjustmentSettings& s, std::string& why)
{
  std::string text;
  std::vector<double> v;
  if (parse_argument(argc, argv, "-soft", text) >= 0) {
    if (!tools::parseNumberList(text, v) || v.size() != 3 || !(v[0] > 0 && v[1] > 0 && v[2] > 0))
      return (why = "-soft takes three positive sigmas t,angle,m").empty();
    s.soft_datum = true;
    s.soft_sigmas << v[0], v[0], v[0], v[1], v[1], v[1], v[2];
  }
  if (!tools::parameterModelOption(argc, argv, {"7", "6", "3", "z", "1"}, s.model, why))
    return false;
  if (parse_argument(argc, argv, "-rule", text) >= 0 && !parseConjugateRuleType(text, s.rule))
    return (why = "-rule takes lnd, lzd or icp").empty();
  std::string estimator_why;
  if (parse_argument(argc, argv, "-estimator", text) >= 0 &&
      !parseRobustEstimatorChoice(text, s.estimator, &estimator_why))
    return (why = "estimator: " + estimator_why).empty();
  if (parse_argument(argc, argv, "-classes", text) >= 0) {
    if (!tools::parseNumberList(text, v))
      return (why = "-classes takes class codes, e.g. 2,6").empty();
    s.stable_classes.clear();
    for (double c : v)
      s.stable_classes.insert(static_cast<std::uint8_t>(c));
  }
  return true;
}

// The numeric options and -one_way. Numbers parsed strictly (tool_options.h): "6x" or "abc" is
// an error, not 6 or 0; ranges stated here, in the options' own names (the settings' isValid()
// speaks of fields).
bool
numericOptions(int argc, char** argv, Options& o, std::string& why)
{
  strips::StripAdjustmentSettings& s = o.request.plan.settings;
  long long count = -1, min_obs = -1;
  if (!tools::numberOption(argc, argv, "-spacing", s.observation_spacing, why, 0.0) ||
      !tools::integerOption(argc, argv, "-max_obs", count, why, 10, 2147483647) ||
      !tools::numberOption(argc, argv, "-max_dist", s.max_distance, why) ||
      !tools::numberOption(argc, argv, "-min_area", s.min_overlap_area, why, 0.0) ||
      !tools::integerOption(argc, argv, "-min_obs", min_obs, why, 1, 2147483647) ||
      !tools::integerOption(argc, argv, "-max_iter", s.adjustment.max_iterations, why, 1, 1000000) ||
      !heldOutZOption(argc, argv, s.adjustment.held_out_z, why) ||
      !tools::numberOption(argc, argv, "-held_out_noise", s.adjustment.held_out_noise_factor, why, 0.0) ||
      !tools::integerOption(argc, argv, "-job", o.job, why, 0, 2147483647) ||
      !tools::integerOption(argc, argv, "-unit", o.unit, why, 0, 2147483647))
    return false;
  if (count >= 0)
    s.max_observations = static_cast<std::size_t>(count);
  if (min_obs >= 0)
    s.min_overlap_observations = static_cast<std::size_t>(min_obs);
  s.both_directions = !find_switch(argc, argv, "-one_way");
  if (tools::optionValue(argc, argv, "-max_dist") && !(s.max_distance > 0.0))
    return (why = "-max_dist must be > 0").empty();
  return true;
}

// -bands, the outputs, -map_format, the switches and -work.
bool
outputOptions(int argc, char** argv, Options& o, std::string& why)
{
  std::string text;
  std::vector<double> v;
  if (parse_argument(argc, argv, "-bands", text) >= 0) {
    if (!tools::parseNumberList(text, v) || v.size() != 2 || !(v[0] > 0 && v[1] > v[0]))
      return (why = "-bands takes two increasing positive limits, e.g. 0.10,0.20").empty();
    o.request.band_inner = v[0];
    o.request.band_outer = v[1];
  }
  parse_argument(argc, argv, "-o", o.request.output_dir);
  parse_argument(argc, argv, "-json", o.request.json_path);
  parse_argument(argc, argv, "-maps", o.request.maps_dir);
  if (parse_argument(argc, argv, "-map_format", text) >= 0 &&
      !maps::parseMapFormat(text, o.request.map_format))
    return (why = "-map_format takes png, pdf or svg, not '" + text + "'").empty();
  o.request.keep_files = find_switch(argc, argv, "-keep_files");
  o.overwrite = find_switch(argc, argv, "-overwrite");
  o.quiet = find_switch(argc, argv, "-q");
  parse_argument(argc, argv, "-work", o.work);
  return true;
}

bool
parseSettings(int argc, char** argv, Options& o, std::string& why)
{
  return stripOptions(argc, argv, o, why) && modelOptions(argc, argv, o.request.plan.settings, why) &&
         numericOptions(argc, argv, o, why) && outputOptions(argc, argv, o, why) &&
         o.request.plan.settings.isValid(&why);
}

// Before any input is read: every input once; the output folder must not hold an input
// (corrected strips would sit beside or replace them) and must be writable, as must the maps
// folder and the report; existing outputs are replaced only with -overwrite.
bool
checkOutputs(const Options& o, std::string& why)
{
  const std::string& dir = o.request.output_dir;
  if (o.request.maps_dir.empty() && o.request.map_format != maps::MapFormat::PNG)
    return (why = "-map_format needs -maps DIR (the maps it formats)").empty();
  for (std::size_t k = 0; k < o.inputs.size(); ++k) {
    const std::string& in = o.inputs[k];
    std::error_code ec;  // no std::filesystem exception escapes: a refused path is one line
    if (!fs::exists(in, ec))
      return (why = in + ": file does not exist").empty();
    for (std::size_t l = 0; l < k; ++l)
      if (io::isSameFile(in, o.inputs[l]))
        return (why = "input " + in + " is given twice (as " + o.inputs[l] + ")").empty();
    if (!dir.empty() && fs::exists(dir, ec) && fs::equivalent(fs::absolute(in, ec).parent_path(), dir, ec))
      return (why = "the output directory " + dir + " holds the input " + in + ": choose another -o").empty();
  }
  if (!dir.empty() && !tools::checkOutputFolder(dir, why))
    return false;
  if (!o.request.maps_dir.empty() && !tools::checkOutputFolder(o.request.maps_dir, why))
    return false;
  return tools::checkOutputFile(o.request.json_path, o.inputs, o.overwrite, why);
}

// A file of the kind the maps folder receives: a GeoTIFF or a map in the chosen format.
bool
isMapFile(const Options& o, const fs::path& path)
{
  return path.extension() == ".tif" || path.extension() == maps::mapExtension(o.request.map_format);
}

// After loading (the split names are known), before the adjustment: no corrected file may
// exist without -overwrite or be the report, and a maps folder must not hold maps already.
bool
checkCorrectedOutputs(const Options& o, const std::vector<strips::OutputUnit>& units, std::string& why)
{
  std::error_code ec;
  for (const auto& u : units) {
    if (!o.request.json_path.empty() && io::isSameFile(u.path, o.request.json_path))
      return (why = "the report " + o.request.json_path + " would replace the corrected strip " + u.path)
          .empty();
    if (fs::exists(u.path, ec) && !o.overwrite)
      return (why = u.path + " exists (use -overwrite to replace it)").empty();
  }
  if (o.request.maps_dir.empty() || o.overwrite)
    return true;
  for (fs::directory_iterator it(o.request.maps_dir, ec), end; !ec && it != end; it.increment(ec))
    if (isMapFile(o, it->path()))
      return (why = "the maps folder " + o.request.maps_dir + " holds maps already (" +
                    it->path().filename().string() + "; use -overwrite to replace them)")
          .empty();
  return true;
}

// -reference IDs → strip indices (point-source ids with -split, else input names).
bool
resolveReferences(const Options& o, const strips::LoadedStrips& block, std::vector<int>& indices,
                  std::string& why)
{
  for (const std::string& id : o.references) {
    int found = -1;
    for (std::size_t k = 0; k < block.sources.size(); ++k) {
      const strips::StripSource& s = block.sources[k];
      if ((s.point_source_id >= 0 && std::to_string(s.point_source_id) == id) || s.name == id)
        found = static_cast<int>(k);
    }
    if (found < 0) {
      std::string names;
      for (const auto& s : block.sources)
        names += (names.empty() ? "" : ", ") +
                 (s.point_source_id >= 0 ? std::to_string(s.point_source_id) : s.name);
      return (why = "unknown reference strip '" + id + "' (strips: " + names + ")").empty();
    }
    indices.push_back(found);
  }
  return true;
}

// Removes outputs that -overwrite allows replacing (never an input).
void
clearOutputs(const Options& o, const std::vector<strips::OutputUnit>& units)
{
  if (!o.overwrite)
    return;
  std::error_code ec;
  for (const auto& u : units)
    fs::remove(u.path, ec);
  if (!o.request.maps_dir.empty())
    for (fs::directory_iterator it(o.request.maps_dir, ec), end; !ec && it != end; it.increment(ec))
      if (isMapFile(o, it->path()))
        fs::remove(it->path(), ec);
}

// Without -split, inputs that each hold several flight lines (point-source ids) overlap as files
// only where the files do: the likely fix, said with the error.
std::string
splitHint(const Options& o, const strips::LoadedStrips& block)
{
  if (o.request.load.split_by_point_source)
    return "";
  for (const auto& f : block.inputs) {
    std::size_t ids = 0;
    for (const auto& kv : f.point_sources)
      ids += kv.first != 0;
    if (ids > 1)
      return " (" + f.path + " holds " + std::to_string(ids) +
             " point-source ids: -split psid makes each a strip)";
  }
  return "";
}

// The length unit's label in the summary: the CRS's, or "units" (the input's) without one.
std::string
unitName(const std::string& wkt)
{
  const std::string name = maps::crsLinearUnitName(wkt);
  return name.empty() ? "units" : name;
}

// -h's exit status of a finished adjustment: 0 a solution, 3 one the checks refused, 2 none.
int
exitStatus(TerminationType t)
{
  if (t == TerminationType::UNRELIABLE)
    return 3;
  return t == TerminationType::CONVERGED || t == TerminationType::MAX_ITERATIONS ? 0 : 2;
}

int
runSingle(Options& o)
{
  TicToc tt;
  tt.tic();
  strips::LoadedStrips block;
  std::string error;
  if (!strips::loadStrips(o.inputs, o.request.load, block, error))
    return fail(error);
  if (!resolveReferences(o, block, o.request.plan.settings.reference_strips, error))
    return fail(error);
  const std::vector<strips::OutputUnit> units =
      o.request.output_dir.empty() ? std::vector<strips::OutputUnit>()
                                   : strips::outputUnits(block, o.request.output_dir, o.request.keep_files);
  if (!checkCorrectedOutputs(o, units, error))
    return fail(error);
  if (!o.quiet)
    print_info("Loaded %zu strips from %zu files in %.1f s, block origin (%.3f, %.3f, %.3f)\n",
               block.strips.size(), block.inputs.size(), tt.toc() / 1000.0, block.block_origin.x(),
               block.block_origin.y(), block.block_origin.z());
  strips::StripBlockAdjustment adjustment;
  adjustment.setSettings(o.request.plan.settings);
  adjustment.setBlockOrigin(block.block_origin);
  if (!o.quiet)
    adjustment.setProgress([](const std::string& line) { print_info("  %s\n", line.c_str()); });
  strips::StripAdjustmentReport report;
  if (!adjustment.run(block.strips, report, error))
    return fail(error + splitHint(o, block));
  report.notes.insert(report.notes.begin(), block.notes.begin(), block.notes.end());
  if (!o.quiet)
    print_info("\n%s\n", strips::reportSummary(report, unitName(block.crs_wkt)).c_str());
  // Outputs: corrected strips, report, maps.
  strips::PlanFile files = o.request;
  files.plan = adjustment.plan();
  files.crs_wkt = block.crs_wkt;
  clearOutputs(o, units);
  std::vector<Eigen::Matrix4d> corrections;
  for (const auto& s : report.strips)
    corrections.push_back(s.parameters == identityParameters() ? Eigen::Matrix4d::Identity()
                                                               : s.transformation);
  std::error_code ec;
  if (!units.empty())
    fs::create_directories(o.request.output_dir, ec);
  for (const auto& u : units)
    if (!strips::writeCorrected(block, u, corrections, error))
      return fail(error);
  std::vector<std::string> maps;
  if (!strips::writeReportAndMaps(files, report, adjustment.samples(), maps, error))
    return fail(error);
  if (!o.quiet)
    print_info("Wrote %zu corrected files, %zu map files%s in %.1f s total\n", units.size(), maps.size(),
               o.request.json_path.empty() ? "" : (", " + o.request.json_path).c_str(), tt.toc() / 1000.0);
  return exitStatus(report.termination);
}

int
runStage(const std::string& stage, Options& o)
{
  if (o.work.empty())
    return fail(stage + " needs -work DIR");
  const strips::WorkDir work{o.work};
  std::string error;
  if (stage == "plan") {
    strips::LoadedStrips probe;
    if (!o.references.empty()) {  // resolve ids against the strips the plan will form
      if (!strips::loadStrips(o.inputs, o.request.load, probe, error) ||
          !resolveReferences(o, probe, o.request.plan.settings.reference_strips, error))
        return fail(error);
    }
    int jobs = 0, units = 0;
    if (!strips::stagePlan(o.inputs, o.request, work, error) ||
        !strips::stageCounts(work, jobs, units, error))
      return fail(error);
    if (!o.quiet)
      print_info("Planned %d match jobs and %d output files in %s\n", jobs, units, o.work.c_str());
    return 0;
  }
  if (stage == "counts") {
    int jobs = 0, units = 0;
    if (!strips::stageCounts(work, jobs, units, error))
      return fail(error);
    print_info("%d %d\n", jobs, units);
    return 0;
  }
  if (stage == "match")
    return o.job >= 0 ? (strips::stageMatch(work, o.job, error) ? 0 : fail(error))
                      : fail("match needs -job K");
  if (stage == "apply")
    return o.unit >= 0 ? (strips::stageApply(work, o.unit, error) ? 0 : fail(error))
                       : fail("apply needs -unit K");
  std::string phase;
  TerminationType termination = TerminationType::CONVERGED;
  if (!strips::stageSolve(work, phase, error, &termination))
    return fail(error);
  print_info("%s\n", phase.c_str());
  return exitStatus(termination);
}

}  // namespace

int
main(int argc, char** argv)
{
  pcl_ls3d::tools::lineBufferedStdout();
  const std::set<std::string> stages = {"plan", "match", "solve", "apply", "counts"};
  const std::string stage = argc > 1 && stages.count(argv[1]) ? argv[1] : "";
  Options o;
  std::string why;
  if (!tools::splitArguments(argc, argv, stage.empty() ? 1 : 2, kWithValue, kSwitches, o.inputs, why))
    return fail(why);
  if (find_switch(argc, argv, "-h") || find_switch(argc, argv, "--help") || argc < 2) {
    printHelp(argv[0]);
    return argc < 2 ? 1 : 0;
  }
  if (!parseSettings(argc, argv, o, why))
    return fail(why);
  if (o.quiet)
    setVerbosityLevel(L_ERROR);
  if (stage.empty() || stage == "plan") {
    if (o.inputs.size() < 2 && !o.request.load.split_by_point_source)
      return fail(o.inputs.empty()
                      ? "no input given (see -h)"
                      : "one strip only: give two or more strips, or -split psid for a file holding several");
    if (o.inputs.empty())
      return fail("no input given (see -h)");
    if (!checkOutputs(o, why))
      return fail(why);
  } else if (!o.inputs.empty())
    return fail("the " + stage + " stage takes no input files");
  return stage.empty() ? runSingle(o) : runStage(stage, o);
}
