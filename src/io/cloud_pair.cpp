#include <pcl_ls3d/io/cloud_pair.h>
#include <pcl_ls3d/maps/coordinate_reference.h>

#include <utility>

namespace pcl_ls3d {
namespace io {

namespace {

using FileCrs = std::pair<std::string, std::string>;  // path, WKT

/// Each file's plan units per height unit (target first), with one note per file converted.
HeightUnits
pairHeightUnits(const std::vector<FileCrs>& files, const std::string& fallback_wkt,
                std::vector<std::string>& notes)
{
  double factor[2] = {1.0, 1.0};
  for (std::size_t i = 0; i < 2; ++i) {
    const bool declared = maps::crsLinearUnit(files[i].second) > 0.0;
    const std::string& wkt =
        declared ? files[i].second : (fallback_wkt.empty() ? files[1 - i].second : fallback_wkt);
    factor[i] = maps::planUnitsPerHeightUnit(wkt);
    if (std::string note = maps::heightConversionNote(files[i].first, wkt, declared, "the matching");
        !note.empty())
      notes.push_back(std::move(note));
  }
  HeightUnits heights;
  heights.target = factor[0];
  heights.source = factor[1];
  return heights;
}

/// (path, WKT) of the inputs; false with the error of the first that is not in lengths.
bool
inputCrs(const std::vector<std::pair<std::string, const CloudInfo*>>& inputs, std::vector<FileCrs>& files,
         std::string& error)
{
  for (const auto& [path, info] : inputs) {
    files.emplace_back(path, maps::crsOfFile(*info));
    if (!(error = maps::notInLengths(path, files.back().second)).empty())
      return false;
  }
  return true;
}

}  // namespace

bool
loadCloudPair(const std::string& target_path, const std::string& source_path, CloudPair& pair,
              std::string& error, const std::string& fallback_wkt)
{
  if (!loadCloud(target_path, *pair.target, pair.target_info, error))
    return false;
  LoadOptions around_target;
  around_target.use_origin = true;
  around_target.origin = pair.target_info.origin;
  if (!loadCloud(source_path, *pair.source, pair.source_info, error, around_target))
    return false;
  std::vector<FileCrs> files;
  if (!inputCrs({{target_path, &pair.target_info}, {source_path, &pair.source_info}}, files, error))
    return false;
  pair.warnings = maps::crsNotes(files);
  pair.heights = pairHeightUnits(files, fallback_wkt, pair.notes);
  pair.working_origin = pairToWorking(pair.heights, pair.target_info.origin, *pair.target, *pair.source);
  return true;
}

}  // namespace io
}  // namespace pcl_ls3d
