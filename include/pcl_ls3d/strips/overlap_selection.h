#pragma once
/// \file overlap_selection.h
/// \brief What one overlap contributes to the adjustment, chosen once: in each direction
///        (i → j and j → i) the observed points of one strip — stable surfaces only, inside the
///        common cells, thinned to a regular spacing — and the surface of the other strip they
///        are matched to (its stable points in the common cells grown by a margin).
///
/// Stable surfaces: on classified strips the classes in settings.stable_classes (ground and
/// buildings by default: vegetation moves and is seen differently from every flight line,
/// water is not a surface); on unclassified strips a roughness test (the RMS distance of the
/// 10 nearest neighbours to their plane below roughness_factor × its median over the overlap).
/// The result is a pure function of the two strips and the footprints, so the single-process
/// run and a distributed match job select exactly the same points.

#include <pcl_ls3d/strips/footprints.h>
#include <pcl_ls3d/strips/strip_adjustment_settings.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace strips {

/// \brief One direction: points of the source strip observed on the target strip's surface.
struct DirectionSelection
{
  int source = -1, target = -1;                 ///< strip indices
  std::vector<Eigen::Vector3d> points;          ///< observed points, source-local coordinates
  std::vector<std::uint32_t> indices;           ///< their indices in the source strip
  pcl::PointCloud<pcl::PointXYZ>::Ptr surface;  ///< target's stable points, target-local
  std::size_t candidates = 0;                   ///< stable source points in the common cells
};

/// \brief Both directions of one overlap.
struct OverlapSelection
{
  DirectionSelection forward;   ///< i → j
  DirectionSelection backward;  ///< j → i
  double spacing = 0.0;         ///< thinning cell edge used
};

/// Selects the observations of overlap `o` (its common cells) between strips o.i and o.j.
OverlapSelection
selectObservations(const std::vector<Strip>& strips, const Overlap& o, const Footprints& footprints,
                   const StripAdjustmentSettings& settings);

/// Thinning: of the points (block XY) in each square cell of edge `spacing`, the index of the
/// one nearest the cell centre (ties: the first), in increasing index order.
std::vector<std::size_t>
thinRegularly(const std::vector<Eigen::Vector2d>& xy, double spacing);

/// Stable-surface flags of the given points of a strip (see the file comment); `region` are
/// the indices the roughness test may use as neighbours (the points near the overlap).
std::vector<std::uint8_t>
stableFlags(const Strip& strip, const std::vector<std::size_t>& region,
            const StripAdjustmentSettings& settings);

}  // namespace strips
}  // namespace pcl_ls3d
