#pragma once
/// \file strip_files.h
/// \brief The files the stages of a distributed strip adjustment exchange through a work
///        directory: the plan (JSON), the state between iterations (JSON + Qxx as raw doubles),
///        each overlap's contribution and its matchers' memory, and the discrepancy samples
///        (binary, little-endian doubles: exact, so a distributed run reproduces the single-
///        process run bit for bit).

#include <pcl_ls3d/adjustment/pair_matcher.h>
#include <pcl_ls3d/maps/map_format.h>
#include <pcl_ls3d/strips/block_solve.h>
#include <pcl_ls3d/strips/strip_block_adjustment.h>
#include <pcl_ls3d/strips/strip_io.h>

#include <array>
#include <string>

namespace pcl_ls3d {
namespace strips {

/// \brief What the plan file holds besides the plan itself: where the strips come from and
///        where the results go.
struct PlanFile
{
  StripPlan plan;
  StripLoadOptions load;
  std::vector<InputFile> inputs;
  std::vector<StripSource> sources;
  std::string crs_wkt;
  std::size_t unassigned = 0;
  std::vector<std::string> load_notes;
  std::string output_dir;  ///< corrected strips ("" = none)
  bool keep_files = false;
  std::string json_path;  ///< report ("" = none)
  std::string maps_dir;   ///< maps ("" = none)
  double band_inner = 0.10, band_outer = 0.20;
  maps::MapFormat map_format = maps::MapFormat::PNG;  ///< of the drawn maps (GeoTIFFs besides)

  /// The loaded-block view the writers take (inputs, sources, origin).
  LoadedStrips
  block() const;
};

bool
writePlanFile(const std::string& path, const PlanFile& plan, std::string& error);
bool
readPlanFile(const std::string& path, PlanFile& plan, std::string& error);

/// A dense matrix as raw doubles (rows, cols, then column-major values).
bool
writeMatrix(const std::string& path, const Eigen::MatrixXd& m, std::string& error);
bool
readMatrix(const std::string& path, Eigen::MatrixXd& m, std::string& error);

/// The state as JSON, its Qxx beside it in path + ".qxx".
bool
writeState(const std::string& path, const BlockState& state, std::string& error);
bool
readState(const std::string& path, BlockState& state, std::string& error);

bool
writeContribution(const std::string& path, const OverlapContribution& c, std::string& error);
bool
readContribution(const std::string& path, OverlapContribution& c, std::string& error);

bool
writeMatcherState(const std::string& path, const std::array<PairMatcher::State, 2>& state,
                  std::string& error);
bool
readMatcherState(const std::string& path, std::array<PairMatcher::State, 2>& state, std::string& error);

bool
writeSamples(const std::string& path, const OverlapSamples& samples, std::string& error);
bool
readSamples(const std::string& path, OverlapSamples& samples, std::string& error);

}  // namespace strips
}  // namespace pcl_ls3d
