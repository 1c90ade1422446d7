#pragma once
/// \file object_assembly.h
/// \brief The object level of IMRG: segments after the §3.2 merging joined into whole objects
///        (ground, a building, a tree group, a car, a wire span). An addition to Wang et al. 2021,
///        whose merging joins fragments into segments but leaves a building as its roof planes
///        and walls and a tree group as crowns. PCL-free.
///
/// Each segment gets a kind from its geometry (segment_kinds.h: ground, linear, rough, wall,
/// solid).
/// First, points of a ground segment that the ground filter rejects (the foot of a hedge, low
/// vegetation, a wall's foot carried along by the planar growth) or that lie clearly above the
/// terrain plane around them (grass; raised_noise_multiple) leave it as their own pieces,
/// one per connected component (detach_raised_points); each piece joins the one non-ground
/// group it has most links with, or stays alone, and never bridges two groups.
/// Segments touch through k-NN links no longer than max_link_length (at least min_links of
/// them). Touching segments join when their kinds belong together: ground with ground; solid
/// and wall with solid and wall (roof planes and walls: a building); rough with rough (a tree
/// group), except that what hangs under a roof (footprint_share of it under the roof's own plan
/// cells, below the roof: a balcony row) and what lies mostly outside every roof (the hedge at
/// the facade's foot) never join. Then, repeated until nothing changes: a linear segment joins
/// the non-linear, non-ground group that at least edge_share of its points touch (an edge line
/// along its roof; a wire span touching its tower with its last points stays a span); a group,
/// not mostly rough, whose contacts go (enclosure_share) to one building at least 20 times its
/// size joins that building (a dormer, a roof window; a rough group — a crown leaning over the
/// roof, or a chimney's scattered returns — joins only by the footprint rule); a group lying in
/// plan (footprint_share of its points) on or under one building's roof, widened by
/// footprint_margin, joins it if it is small beside it (a chimney whose k-NN links never leave
/// it: enclosure_size_ratio) or if those points also lie below the roof, whatever its size (a
/// facade with balconies under the eaves of a roof strip that the tile edge left, a lower
/// annex under the eaves; a crown over a roof lies above it). Above the roof only what stands
/// on it counts: a point higher than the roof in the margin, where the margin opens onto what
/// lies beyond the roof, is off the footprint (a crown overhanging the eave stays a tree; the
/// cells a roof unit hides under itself are enclosed and count). A building stays one after a
/// rough facade has joined it. Nothing joins the ground, and lines never join lines: two spans
/// of a wire meet end to end at their tower.
/// Kinds come from the segments before any join, so the joins do not depend on their order.

#include <pcl_ls3d/segmentation/segment_adjacency.h>
#include <pcl_ls3d/segmentation/segment_kinds.h>

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {

/// \brief Settings of assembleObjects(); lengths in cloud units.
struct AssemblySettings
{
  KindSettings kinds;                 ///< what makes a segment ground, linear, rough, wall, solid
  std::size_t min_links = 3;          ///< weaker contacts never join
  double max_link_length = 1.0;       ///< longer k-NN links do not make segments touch (the class
                                      ///< sets its growth radius)
  double rough_link_length = 0.0;     ///< rough segments (crowns) touch each other only through
                                      ///< links this short (the class sets its volumetric radius);
                                      ///< ≤ 0: max_link_length
  double edge_share = 0.25;           ///< share of a linear segment's points touching a group to
                                      ///< join it (a wire span touches its tower with about 10 %)
  double enclosure_share = 0.8;       ///< share of a group's contacts with one building to join it
  double enclosure_size_ratio = 0.2;  ///< ... if at most this fraction of the building's size
  double footprint_share = 0.8;       ///< share of a group's points on or under one building's roof
                                      ///< (in plan) to join it, if at most enclosure_size_ratio of it
                                      ///< or if that share also lies below the roof
  double footprint_margin = 0.75;     ///< the roof's plan reaches this far past its points (eaves,
                                      ///< balconies: for what lies below the roof; above it, only
                                      ///< margin cells enclosed by the roof count)
  bool detach_raised_points = true;   ///< points of a ground segment that the ground filter
                                      ///< rejects leave it as their own segments
  /// ... and so do those it keeps that lie more than this many ground residuals (the
  /// terrain's noise, AssemblyReport::ground_residual, an RMS: about σ) above the terrain plane
  /// of the ground points around them (heightAboveTerrain, terrainWindowHalfWidth()):
  /// grass 5–30 cm high, which the filter keeps up to its initial distance. 6 scored best of
  /// 4, 6, 8 on the tuning tiles (docs/BENCHMARKS.md). ≤ 0: the filter alone.
  double raised_noise_multiple = 6.0;
  /// After the classes (MultiRuleRegionGrowing): vegetation and car points the filter keeps no
  /// higher than this many ground residuals above that terrain plane are the ground under a
  /// crown's rim or beside a car and join the ground (terrain_contact.h). 3: the terrain's
  /// noise at 3 σ. ≤ 0: off.
  double terrain_return_multiple = 3.0;
  /// After the classes: vegetation points under a building's roof join it (roof_cover.h).
  bool claim_under_roofs = true;
};

/// \brief Half width of the window of the terrain plane that heights are taken above
///        (heightAboveTerrain): two link lengths, about four growth radii across.
inline double
terrainWindowHalfWidth(const AssemblySettings& settings)
{
  return 2.0 * settings.max_link_length;
}

/// \brief The links through which a fragment left after the assembly may be absorbed
///        (absorbFragments' linkable). A link p → q counts only when it is no longer than
///        \a max_link_length (the growth radius: as far apart as points of two segments the
///        assembly calls touching may be) and does not lead from a rough point into a
///        ground-kind point. A bush of a few points on a lawn then stays its own object: its
///        ground links do not count, and neither do the long k-NN links that reach the crown of
///        a tree metres away. One such link is enough (the assembly asks for min_links): a
///        fragment has few points.
/// \param[in] points coordinates per point (positions as in the graph)
/// \param[in] point_kind per point: kind of its segment before any join
///            (AssemblyReport::point_kind); both vectors must outlive the returned rule, which
///            counts no link when their sizes differ
/// \param[in] max_link_length longest contact [cloud units] (AssemblySettings::max_link_length)
std::function<bool(int, int)>
absorptionContact(const std::vector<Eigen::Vector3f>& points, const std::vector<SegmentKind>& point_kind,
                  double max_link_length);

/// \brief What assembleObjects() did.
struct AssemblyReport
{
  std::size_t segments_before = 0, objects = 0;
  std::size_t detached_points = 0;              ///< points that left ground segments (raised above terrain)
  std::size_t points_under_roofs = 0;           ///< vegetation points that joined a roof above them
  std::size_t points_back_to_ground = 0;        ///< vegetation points that joined the ground
  std::size_t kind_count[5] = {0, 0, 0, 0, 0};  ///< segments per SegmentKind
  double ground_residual = 0.0;                 ///< median residual of the ground points (roughness unit)
  /// per point: kind of its segment before any join (pieces detached from the ground by their
  /// own kind); what classifyObjects() votes with. Solid for points in no segment.
  std::vector<SegmentKind> point_kind;
};

/// \brief Joins touching segments into objects by the rules of the file comment; \a labels is
///        relabelled densely (−1 stays −1).
/// \param[in] points coordinates per point
/// \param[in] graph k-NN graph, \a graph_k positions per point, −1 padded
/// \param[in] residuals plane-fit residual per point (PointFeatures::residual)
/// \param[in] ground per point: 1 if the ground filter keeps it
/// \param[in,out] labels segment per point (dense 0..n−1, −1 none)
AssemblyReport
assembleObjects(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& graph, int graph_k,
                const std::vector<float>& residuals, const std::vector<char>& ground,
                const AssemblySettings& settings, std::vector<int>& labels);

}  // namespace segmentation
}  // namespace pcl_ls3d
