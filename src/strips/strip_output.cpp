// Corrected strips out (strip_io.h): LAS by a record-level rewrite, other formats through the
// project's writers; and strips from a cloud in memory.
#include <pcl_ls3d/common/height_units.h>
#include <pcl_ls3d/io/las_records.h>
#include <pcl_ls3d/io/las_rewrite.h>
#include <pcl_ls3d/io/strip_tools.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/strips/strip_io.h>

#include <filesystem>
#include <map>

namespace pcl_ls3d {
namespace strips {

namespace fs = std::filesystem;

namespace {

// Strip index of a point: by point-source id when split, else the file's strip (−1: none).
struct StripLookup
{
  bool split = false;
  std::map<int, int> by_id;
  int file_strip = -1;

  StripLookup(const LoadedStrips& block, int file)
  {
    for (std::size_t k = 0; k < block.sources.size(); ++k) {
      const StripSource& s = block.sources[k];
      if (s.point_source_id >= 0) {
        split = true;
        by_id[s.point_source_id] = static_cast<int>(k);
      } else if (std::find(s.files.begin(), s.files.end(), file) != s.files.end())
        file_strip = static_cast<int>(k);
    }
  }
  int
  operator()(int point_source_id) const
  {
    if (!split)
      return file_strip;
    const auto it = by_id.find(point_source_id);
    return it == by_id.end() ? -1 : it->second;
  }
};

bool
refuse(const LoadedStrips& block, const std::string& path, std::string& error)
{
  for (const InputFile& in : block.inputs)
    if (fs::exists(path) && io::isSameFile(in.path, path)) {
      error = "the output " + path + " is an input: refusing to overwrite it";
      return true;
    }
  if (fs::exists(path)) {
    error = path + " exists (not overwritten)";
    return true;
  }
  return false;
}

}  // namespace

bool
writeCorrected(const LoadedStrips& block, const OutputUnit& unit,
               const std::vector<Eigen::Matrix4d>& corrections, std::string& error)
{
  if (refuse(block, unit.path, error))
    return false;
  const InputFile& input = block.inputs[static_cast<std::size_t>(unit.file)];
  const StripLookup lookup(block, unit.file);
  // The block was adjusted with heights in the plan unit; the file keeps its own.
  const double f = heightFactor(block.inputs, static_cast<std::size_t>(unit.file));
  std::vector<Eigen::Matrix4d> in_file_units = corrections;
  for (Eigen::Matrix4d& T : in_file_units)
    T = HeightUnits::ofOneFile(f).toFiles(T);
  auto correction = [&](int psid) -> const Eigen::Matrix4d* {
    const int k = lookup(psid);
    if (k < 0 || static_cast<std::size_t>(k) >= in_file_units.size() ||
        in_file_units[static_cast<std::size_t>(k)].isIdentity(0.0))
      return nullptr;
    return &in_file_units[static_cast<std::size_t>(k)];
  };
  if (input.format == "las") {
    io::LasRecordFile las;
    if (!las.open(input.path, error))
      return false;
    std::vector<std::size_t> selection;
    if (unit.point_source_id >= 0)
      for (std::size_t i = 0; i < las.size(); ++i)
        if (las.pointSourceId(i) == unit.point_source_id)
          selection.push_back(i);
    io::LasRewriteSummary summary;
    return io::rewriteLas(
        las, unit.point_source_id >= 0 ? &selection : nullptr,
        [&](std::size_t i, Eigen::Vector3d& x) {
          const Eigen::Matrix4d* T = correction(las.pointSourceId(i));
          if (!T)
            return false;
          x = (*T * x.homogeneous()).head<3>();
          return true;
        },
        unit.path, summary, error);
  }
  pcl::PointCloud<PointLiDAR> cloud, out;
  io::CloudInfo info;
  if (!io::loadCloud(input.path, cloud, info, error))
    return false;
  for (const PointLiDAR& p : cloud) {
    if (unit.point_source_id >= 0 && p.point_source_id != unit.point_source_id)
      continue;
    PointLiDAR q = p;
    if (const Eigen::Matrix4d* T = correction(p.point_source_id)) {
      const Eigen::Vector3d x = info.origin + p.getVector3fMap().cast<double>();
      q.getVector3fMap() = ((*T * x.homogeneous()).head<3>() - info.origin).cast<float>();
    }
    out.push_back(q);
  }
  io::SaveOptions options;
  maps::recordCrs(maps::crsOfFile(info), options);
  return io::saveCloud(unit.path, out, info.origin, error, options);
}

std::vector<Strip>
stripsFromCloud(const pcl::PointCloud<PointLiDAR>& cloud, bool split)
{
  std::vector<Strip> out;
  std::map<std::uint16_t, pcl::Indices> groups;
  if (split)
    groups = io::splitByPointSource(cloud);
  else {
    pcl::Indices all(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i)
      all[i] = static_cast<int>(i);
    groups[0] = all;
  }
  for (const auto& kv : groups) {
    if (split && kv.first == 0)
      continue;
    std::vector<Eigen::Vector3d> pts;
    std::vector<std::uint8_t> cls;
    pts.reserve(kv.second.size());
    for (int i : kv.second) {
      pts.push_back(cloud[static_cast<std::size_t>(i)].getVector3fMap().cast<double>());
      cls.push_back(cloud[static_cast<std::size_t>(i)].classification);
    }
    out.push_back(
        makeStrip(split ? "psid" + std::to_string(kv.first) : "cloud", split ? kv.first : -1, pts, cls));
  }
  return out;
}

}  // namespace strips
}  // namespace pcl_ls3d
