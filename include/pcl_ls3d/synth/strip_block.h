#pragma once
/// \file strip_block.h
/// \brief Airborne-like flight strips over the synthetic terrain, each strip displaced by its
///        own known 7-parameter similarity (the errors a strip adjustment must remove).
///
/// Geometry (block-local frame, the TRUE frame; metres, seconds):
///  - Cross strips (optional) come after the N parallel ones: flown along a, across the whole
///    block (length (N−1)·spacing + swath), centred at along = ((c + ½)/C − ½)·length for
///    c = 0..C−1, with the same swath, density and scan pattern.
///  - Flight direction d = (cos heading, sin heading), across a = (−sin heading, cos heading).
///    Strip s (0-based) flies along the line through c_s = (s − (N−1)/2)·spacing·a, with
///    spacing = swath_width·(1 − side_overlap), from −length/2 to +length/2 along d. So
///    neighbouring swaths share side_overlap·swath_width across track.
///  - Scan lines across track: n_c = max(1, round(swath·√density)) points per line at spacing
///    swath/n_c, lines da = 1/(density·swath/n_c) apart along track, so the nominal density is
///    exact. Point j of line k sits at across = (j + ½)/n_c·swath − swath/2 (reversed on odd
///    lines for ZIGZAG) and along = −length/2 + (k + (j + ½)/n_c)·da: the aircraft advances
///    while the mirror sweeps, which draws the zig-zag (oscillating mirror) or the parallel slanted
///    lines (rotating polygon) on the ground. With line_phase each scan line is moved by its
///    own random fraction of a spacing: across by (u − ½)·swath/n_c (point j at
///    (j + u)/n_c·swath − swath/2), along by (v − ½)·da, u, v ~ U[0, 1) (the aircraft's roll
///    and pitch move whole lines); gps_time keeps the unmoved along.
///  - True point: that (x, y), z = what a pulse from above hits there (landscape.h: terrain and
///    roofs; urban and mountainous scenes add trees, roads, terraces, scarps), plus isotropic
///    noise.
///    OBSERVED point (what the cloud holds) = truth[s].transform.inverse() applied to it, so
///    truth[s].transform maps strip s's observed coordinates onto the true frame.
///  - gps_time = start_time + s·(length/speed + turn_time) + (k + (j + ½)/n_c)·da/speed.
///    point_source_id = first_source_id + s. Classification 2 ground / 6 roof / 5 tree crown;
///    return 1 of 1.
///  - Clouds hold local coordinates; written coordinates = local + origin.

#include <pcl_ls3d/common/similarity_transform.h>
#include <pcl_ls3d/point_types.h>
#include <pcl_ls3d/synth/buildings.h>
#include <pcl_ls3d/synth/landscape.h>

#include <pcl/point_cloud.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace synth {

enum class ScanPattern : std::uint8_t
{
  ZIGZAG = 0,
  PARALLEL = 1
};

/// \brief Settings of makeStripBlock().
struct StripSettings
{
  std::uint32_t seed = 1;
  int num_strips = 3;           ///< parallel strips
  int cross_strips = 0;         ///< strips across them (after the parallel ones)
  double heading = 0.0;         ///< flight direction from +x [rad]
  double strip_length = 600.0;  ///< [m]
  double swath_width = 300.0;   ///< [m]
  double side_overlap = 0.3;    ///< shared fraction of the swath between neighbours, [0, 1)
  double density = 4.0;         ///< nominal points per m² within a strip
  ScanPattern pattern = ScanPattern::ZIGZAG;
  double speed = 60.0;        ///< ground speed [m/s] (gps_time)
  double start_time = 0.0;    ///< gps_time of the first point [s]
  double turn_time = 120.0;   ///< time between strips [s]
  double noise_sigma = 0.05;  ///< isotropic noise per axis [m]
  double relief = 10.0;       ///< Terrain relief [m]
  double wavelength = 60.0;   ///< Terrain wavelength [m]
  bool buildings = true;
  BuildingSettings building_settings;
  LandscapeSettings landscape;  ///< trees, roads, terraces, scarps (ROLLING: none)
  std::uint16_t first_source_id = 1;
  /// Strip 1 is the fixed reference (identity truth).
  bool fix_first = true;
  /// Random per-strip errors (when `transforms` is empty), drawn about the strip centre:
  /// shift per axis N(0, shift_sigma) [m], angles N(0, angle_sigma) [rad], m − 1 ~ N(0, scale_sigma).
  double shift_sigma = 0.15, angle_sigma = 3e-4, scale_sigma = 5e-5;
  /// Explicit per-strip errors about each strip's centre, as the random ones (tx ty tz [m],
  /// φ ω κ [rad], m); one per strip (parallel, then cross) or empty. A fixed first strip keeps
  /// the identity.
  std::vector<Vector7d> errors;
  /// Explicit per-strip truths (block-local frame, observed → true); one per strip or empty.
  /// Takes precedence over `errors`.
  std::vector<SimilarityTransform> transforms;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< georeference offset
  /// Move each scan line by its own random fraction of the point spacing, across and along
  /// track (own random stream, so the truths do not change). Real strips never sample the
  /// ground on one regular lattice; on aligned lattices every corrected pair meets at one
  /// sampling phase, where the surface rules' small phase-dependent noise bias (a few mm at
  /// 5 cm noise) no longer averages out and the σ are too optimistic (docs/BENCHMARKS.md,
  /// "Monte-Carlo σ coverage"). false: the regular lattice (u = v = ½).
  bool line_phase = true;

  int
  totalStrips() const
  {
    return num_strips + cross_strips;
  }
  bool
  isValid(std::string* why = nullptr) const;
};

/// Sets the scene of a Zuo et al. (2012) Table 1-like block: URBAN (Hebei: 4 m relief, dense
/// flat/gable/hip buildings, trees, a road grid) or MOUNTAIN (Henan: 60 m relief, 2.5 m
/// terraces, four 4–10 m scarps, isolated trees, a few low buildings); ROLLING: the defaults.
/// Strip geometry, density, noise and errors are left as they are.
void
setScene(StripSettings& settings, LandscapeType type);

/// \brief What is known about one strip.
struct StripTruth
{
  std::uint16_t point_source_id = 0;
  bool cross = false;             ///< a cross strip
  bool fixed = false;             ///< the reference strip (identity)
  SimilarityTransform transform;  ///< observed → true, block-local frame (rotation about 0)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< strip centre c_s (true frame, z = 0)
  /// The same map written about the centre: x' = centre + t_centre + m R (x − centre).
  Eigen::Vector3d t_centre = Eigen::Vector3d::Zero();
  std::array<Eigen::Vector2d, 4>
      footprint;  ///< true-frame corners (start-left, start-right, end-right, end-left)
  std::size_t first_index = 0, point_count = 0;  ///< the strip's points in the block cloud
  std::size_t scan_lines = 0, points_per_line = 0;
  double start_time = 0.0, end_time = 0.0;  ///< [s]
};

/// \brief All strips in one cloud (ordered by strip, then by time) and the per-strip truths.
struct StripBlock
{
  pcl::PointCloud<PointLiDAR>::Ptr cloud;
  std::vector<StripTruth> strips;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  std::shared_ptr<const SurfaceModel> surface;           ///< terrain + roofs (ROLLING: the true surface)
  std::shared_ptr<const Landscape> landscape;            ///< the true scene
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  ///< d
  double strip_spacing = 0.0;                            ///< distance between neighbouring centre lines [m]

  /// The points of strip s (copy).
  pcl::PointCloud<PointLiDAR>::Ptr
  stripCloud(std::size_t s) const;
};

/// Generates the block; deterministic in the seed (independent of thread count). Invalid
/// settings: PCL_ERROR and an empty (non-null) cloud.
StripBlock
makeStripBlock(const StripSettings& settings);

}  // namespace synth
}  // namespace pcl_ls3d
