// Strips from files (strip_io.h): two passes over each strip's points (origin, then local
// coordinates), LAS read record by record.
#include <pcl_ls3d/io/las_records.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/strips/strip_io.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <set>

namespace pcl_ls3d {
namespace strips {

namespace fs = std::filesystem;

namespace {

// An opened input: raw LAS records, or a cloud read by the project's readers.
struct OpenInput
{
  io::LasRecordFile las;
  pcl::PointCloud<PointLiDAR> cloud;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // cloud: file = local + origin
  bool is_las = false;
  // Plan units per height unit (heightFactor()): the block is adjusted with heights in the plan
  // unit.
  double height_factor = 1.0;
};

bool
isLas(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  char sig[4] = {};
  in.read(sig, 4);
  return (in.gcount() == 4 && std::string(sig, 4) == "LASF") || io::fileExtension(path) == "laz";
}

bool
openInput(const std::string& path, OpenInput& in, InputFile& info, std::string& error)
{
  info.path = path;
  if (!fs::exists(path)) {
    error = path + ": file does not exist";
    return false;
  }
  in.is_las = isLas(path);
  if (in.is_las) {
    if (!in.las.open(path, error))
      return false;
    info.format = "las";
    info.points = in.las.size();
    info.crs_wkt = maps::crsFromLasVlrs(in.las.header().vlrs);
    if (!(error = maps::notInLengths(path, info.crs_wkt)).empty())
      return false;  // in degrees a wrong answer would still converge
    for (std::size_t i = 0; i < in.las.size(); ++i)
      ++info.point_sources[in.las.pointSourceId(i)];
    return true;
  }
  io::CloudInfo ci;
  if (!io::loadCloud(path, in.cloud, ci, error)) {
    if (error.rfind(path, 0) != 0)  // loadCloud names the file itself in most of its reasons
      error = path + ": " + error;
    return false;
  }
  info.crs_wkt = maps::crsOfFile(ci);
  if (!(error = maps::notInLengths(path, info.crs_wkt)).empty())
    return false;
  info.format = ci.format;
  info.points = in.cloud.size();
  in.origin = ci.origin;
  for (const PointLiDAR& p : in.cloud)
    ++info.point_sources[p.point_source_id];
  return true;
}

// One point as the strip builder sees it.
struct PointView
{
  Eigen::Vector3d x;  // file coordinates
  std::uint8_t classification = 0;
  bool withheld = false, synthetic = false;
};

// Calls fn for every point of `source` in file order, then record order.
void
forEachPoint(const std::vector<OpenInput>& open, const StripSource& source,
             const std::function<void(const PointView&)>& fn)
{
  PointView v;
  for (int f : source.files) {
    const OpenInput& in = open[static_cast<std::size_t>(f)];
    if (in.is_las) {
      for (std::size_t i = 0; i < in.las.size(); ++i) {
        if (source.point_source_id >= 0 && in.las.pointSourceId(i) != source.point_source_id)
          continue;
        v.x = in.las.coordinates(i);
        v.x.z() *= in.height_factor;
        v.classification = in.las.classification(i);
        const io::LasPointFlags flags = in.las.flags(i);
        v.withheld = flags.withheld;
        v.synthetic = flags.synthetic;
        fn(v);
      }
      continue;
    }
    for (const PointLiDAR& p : in.cloud) {
      if (source.point_source_id >= 0 && p.point_source_id != source.point_source_id)
        continue;
      v.x = in.origin + p.getVector3fMap().cast<double>();
      v.x.z() *= in.height_factor;
      v.classification = p.classification;
      v.withheld = v.synthetic = false;
      fn(v);
    }
  }
}

// Pass 2: local coordinates about the file-space origin F_k = O + o_k.
Strip
buildStrip(const std::vector<OpenInput>& open, const StripSource& source, const Eigen::Vector3d& block_origin,
           const StripLoadOptions& options)
{
  Strip s;
  s.name = source.name;
  s.point_source_id = source.point_source_id;
  s.origin = source.file_origin - block_origin;
  forEachPoint(open, source, [&](const PointView& v) {
    s.points.push_back((v.x - source.file_origin).cast<float>());
    s.classification.push_back(v.classification);
    const bool out = (options.exclude_withheld && v.withheld) || (options.exclude_synthetic && v.synthetic);
    s.excluded.withheld += options.exclude_withheld && v.withheld;
    s.excluded.synthetic +=
        options.exclude_synthetic && v.synthetic && !(options.exclude_withheld && v.withheld);
    s.observable.push_back(out ? 0 : 1);
  });
  return s;
}

std::string
stem(const std::string& path)
{
  return fs::path(path).stem().string();
}

}  // namespace

namespace {

// Opens every input; the block's CRS is the first declared one, the others noted where they differ.
bool
openInputs(const std::vector<std::string>& paths, std::vector<OpenInput>& open, LoadedStrips& out,
           std::string& error)
{
  std::vector<std::pair<std::string, std::string>> crs_of_file;
  for (std::size_t f = 0; f < paths.size(); ++f) {
    InputFile info;
    if (!openInput(paths[f], open[f], info, error))
      return false;
    if (out.crs_wkt.empty())
      out.crs_wkt = info.crs_wkt;
    crs_of_file.emplace_back(info.path, info.crs_wkt);
    out.inputs.push_back(std::move(info));
  }
  for (std::string& note : maps::crsNotes(crs_of_file))
    out.notes.push_back(std::move(note));
  return true;
}

// Each input's heights into the plan unit, with one note per input converted.
void
setHeightFactors(const std::vector<std::string>& paths, std::vector<OpenInput>& open, LoadedStrips& out)
{
  for (std::size_t f = 0; f < paths.size(); ++f) {
    open[f].height_factor = heightFactor(out.inputs, f);
    const bool declared = maps::crsLinearUnit(out.inputs[f].crs_wkt) > 0.0;
    if (std::string note =
            maps::heightConversionNote(paths[f], heightCrs(out.inputs, f), declared, "the adjustment");
        !note.empty())
      out.notes.push_back(std::move(note));
  }
}

// One strip per non-zero point-source id over all inputs (id 0: no strip, written unchanged).
bool
splitByPointSource(LoadedStrips& out, std::string& error)
{
  std::map<int, std::vector<int>> ids;
  for (std::size_t f = 0; f < out.inputs.size(); ++f)
    for (const auto& kv : out.inputs[f].point_sources) {
      if (kv.first == 0)
        out.unassigned += kv.second;
      else
        ids[kv.first].push_back(static_cast<int>(f));
    }
  if (ids.size() < 2) {
    error = ids.empty() ? "the split by point-source id finds no strip (every point has id 0)"
                        : "the split by point-source id finds one strip only (id " +
                              std::to_string(ids.begin()->first) + ")";
    return false;
  }
  for (const auto& kv : ids)
    out.sources.push_back({"psid" + std::to_string(kv.first), kv.first, kv.second, {}});
  if (out.unassigned > 0)
    out.notes.push_back(std::to_string(out.unassigned) +
                        " points with point-source id 0 belong to no strip: not observed, written unchanged");
  for (const InputFile& f : out.inputs)
    if (f.points == 0)
      out.notes.push_back(f.path + " has no points: no strip from it");
  return true;
}

// Pass 1: each strip's origin F_k (rounded XY box centre, rounded mean height) and the block's
// origin (rounded centre of all boxes, height 0).
bool
placeOrigins(const std::vector<OpenInput>& open, LoadedStrips& out, std::string& error)
{
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (StripSource& src : out.sources) {
    Eigen::Vector2d slo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), shi = -slo;
    double z = 0.0;
    std::size_t n = 0;
    forEachPoint(open, src, [&](const PointView& v) {
      slo = slo.cwiseMin(v.x.head<2>());
      shi = shi.cwiseMax(v.x.head<2>());
      z += v.x.z();
      ++n;
    });
    if (n == 0) {
      error = "strip " + src.name + " has no points";
      return false;
    }
    const Eigen::Vector2d c = 0.5 * (slo + shi);
    src.file_origin =
        Eigen::Vector3d(std::round(c.x()), std::round(c.y()), std::round(z / static_cast<double>(n)));
    lo = lo.cwiseMin(slo);
    hi = hi.cwiseMax(shi);
  }
  const Eigen::Vector2d c = 0.5 * (lo + hi);
  out.block_origin = Eigen::Vector3d(std::round(c.x()), std::round(c.y()), 0.0);
  return true;
}

// Pass 2: local coordinates, classes and exclusions of every strip, with a note on the excluded.
void
buildStrips(const std::vector<OpenInput>& open, const StripLoadOptions& options, LoadedStrips& out)
{
  for (const StripSource& src : out.sources)
    out.strips.push_back(buildStrip(open, src, out.block_origin, options));
  std::size_t withheld = 0, synthetic = 0;
  for (const Strip& s : out.strips) {
    withheld += s.excluded.withheld;
    synthetic += s.excluded.synthetic;
  }
  if (withheld + synthetic > 0)
    out.notes.push_back(std::to_string(withheld) + " withheld and " + std::to_string(synthetic) +
                        " synthetic points are not observed (they are corrected and written)");
}

}  // namespace

bool
loadStrips(const std::vector<std::string>& paths, const StripLoadOptions& options, LoadedStrips& out,
           std::string& error)
{
  out = LoadedStrips();
  std::vector<OpenInput> open(paths.size());
  if (!openInputs(paths, open, out, error))
    return false;
  setHeightFactors(paths, open, out);
  if (options.split_by_point_source) {
    if (!splitByPointSource(out, error))
      return false;
  } else
    for (std::size_t f = 0; f < out.inputs.size(); ++f)
      out.sources.push_back({stem(paths[f]), -1, {static_cast<int>(f)}, {}});
  if (!placeOrigins(open, out, error))
    return false;
  buildStrips(open, options, out);
  return true;
}

const std::string&
heightCrs(const std::vector<InputFile>& inputs, std::size_t f)
{
  if (maps::crsLinearUnit(inputs[f].crs_wkt) > 0.0)
    return inputs[f].crs_wkt;
  for (const InputFile& in : inputs)
    if (maps::crsLinearUnit(in.crs_wkt) > 0.0)
      return in.crs_wkt;
  return inputs[f].crs_wkt;
}

double
heightFactor(const std::vector<InputFile>& inputs, std::size_t f)
{
  return maps::planUnitsPerHeightUnit(heightCrs(inputs, f));
}

bool
loadStrip(const std::vector<InputFile>& inputs, const StripSource& source,
          const Eigen::Vector3d& block_origin, const StripLoadOptions& options, Strip& strip,
          std::string& error)
{
  std::vector<OpenInput> open(inputs.size());
  for (int f : source.files) {
    InputFile info;
    if (!openInput(inputs[static_cast<std::size_t>(f)].path, open[static_cast<std::size_t>(f)], info, error))
      return false;
    open[static_cast<std::size_t>(f)].height_factor = heightFactor(inputs, static_cast<std::size_t>(f));
  }
  strip = buildStrip(open, source, block_origin, options);
  return true;
}

namespace {

// A corrected COPC file is written as plain LAZ (its records move, so the octree would no longer
// hold them): "x.copc.laz" gives "x" and ".laz", any other name its stem and extension.
std::pair<std::string, std::string>
outputStemAndExtension(const fs::path& in)
{
  std::string stem = in.stem().string();
  const std::string ext = in.extension().string();
  if (stem.size() > 5 && io::fileExtension(stem) == "copc" && io::fileExtension(in.filename()) == "laz")
    stem.erase(stem.size() - 5);
  return {stem, ext};
}

}  // namespace

std::vector<OutputUnit>
outputUnits(const LoadedStrips& block, const std::string& dir, bool keep_files)
{
  std::vector<OutputUnit> units;
  const bool split = !block.sources.empty() && block.sources[0].point_source_id >= 0;
  for (std::size_t f = 0; f < block.inputs.size(); ++f) {
    const auto [stem, ext] = outputStemAndExtension(block.inputs[f].path);
    if (!split || keep_files) {
      units.push_back({static_cast<int>(f), -1, (fs::path(dir) / (stem + ext)).string()});
      continue;
    }
    for (const auto& kv : block.inputs[f].point_sources) {
      const std::string name = stem + "_psid" + std::to_string(kv.first) + ext;
      units.push_back({static_cast<int>(f), kv.first, (fs::path(dir) / name).string()});
    }
  }
  return units;
}

}  // namespace strips
}  // namespace pcl_ls3d
