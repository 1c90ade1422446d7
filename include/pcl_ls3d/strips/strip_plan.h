#pragma once
/// \file strip_plan.h
/// \brief Stage "plan" of the strip adjustment: what every later stage needs to know about the
///        block before any matching — the strips (names, origins, radii), the footprint grid, the
///        overlap graph with skipped pairs, the datum (reference strips or soft weights) and the
///        parameter blocks it implies. A distributed run writes it once (strip_files.h).

#include <pcl_ls3d/adjustment/gauss_markov.h>
#include <pcl_ls3d/adjustment/parameter_block.h>
#include <pcl_ls3d/maps/raster.h>
#include <pcl_ls3d/strips/footprints.h>
#include <pcl_ls3d/strips/strip_adjustment_settings.h>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace strips {

/// \brief What the plan keeps of one strip.
struct PlannedStrip
{
  std::string name;
  int point_source_id = -1;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< o_k, block coordinates
  std::size_t points = 0, observable = 0;
  ExclusionCounts excluded;
  double density = 0.0;     ///< points per unit² over its footprint
  double radius = 0.0;      ///< largest horizontal distance of a point from o_k
  int part = -1;            ///< connected part of the overlap graph (−1: no overlap)
  bool reference = false;   ///< fixed datum strip
  bool classified = false;  ///< stable surfaces by class (else by roughness)
};

/// \brief The plan.
struct StripPlan
{
  StripAdjustmentSettings settings;
  Eigen::Vector3d block_origin = Eigen::Vector3d::Zero();  ///< file coordinates = block + this
  std::vector<PlannedStrip> strips;
  maps::GridGeometry grid;         ///< footprint grid (block coordinates)
  std::vector<Overlap> overlaps;   ///< all pairs with common cells (cells may be cleared)
  double precision_cell = 0.0;     ///< edge of the spatial precision cells
  std::vector<std::string> notes;  ///< datum choices and warnings, for the report

  /// Indices of the used overlaps (the match jobs).
  std::vector<int>
  jobs() const;
  /// The parameter blocks at the start: identity about each o_k, a-priori observations of the
  /// model and the datum (soft weights scaled by σ_obs², see settings.soft_datum).
  std::vector<ParameterBlock>
  initialBlocks(double soft_sigma_obs = 1.0) const;
  /// The solve's problem for the given current values (rank-test scaling per strip radius).
  GaussMarkovProblem
  problem(const std::vector<ParameterBlock>& blocks) const;
};

/// Builds the plan: footprints, overlaps (small ones skipped), connected parts, datum. Returns
/// false with a one-line reason when the block cannot be adjusted (fewer than two strips, no
/// used overlap, a reference index out of range).
bool
makePlan(const std::vector<Strip>& strips, const StripAdjustmentSettings& settings, StripPlan& plan,
         std::string& error, Footprints* footprints = nullptr);

}  // namespace strips
}  // namespace pcl_ls3d
