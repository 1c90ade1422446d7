#pragma once
/// \file segmentation_runner.h
/// \brief Runs one segmentation method on a cloud with timings and the figures a report needs:
///        IMRG, MRG (pcl_ls3d::MultiRuleRegionGrowing), PCL's own normals + pcl::RegionGrowing,
///        or the voxel-grid baseline. Shared by pcl_ls3d_segment, the benchmark and the tests so
///        all three run the same thing.

#include <pcl_ls3d/evaluation/segmentation_metrics.h>
#include <pcl_ls3d/segmentation/object_classes.h>

#include <pcl/PointIndices.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// \brief The methods compared.
enum class SegmentationMethod
{
  IMRG,              ///< MultiRuleRegionGrowing, Mode::IMRG (seed condition + 3-rule merging)
  MRG,               ///< MultiRuleRegionGrowing, Mode::MRG (no seed condition, distance merging)
  PclRegionGrowing,  ///< pcl::NormalEstimationOMP + pcl::RegionGrowing; points in no cluster
                     ///< (clusters under the minimum size) form one "rest" segment
  VoxelGrid          ///< non-empty voxels, edge chosen for voxel_segments segments
};

/// \brief Which IMRG/MRG stage is returned: the planes of the growing stage (Table 1 of the
///        paper, before merging) or whole objects (after merging).
enum class SegmentationLevel
{
  Planes,
  Objects
};

/// "imrg" / "mrg" / "pcl_rg" / "voxel" and back. parse returns false for anything else.
std::string
toString(SegmentationMethod m);
bool
parseSegmentationMethod(const std::string& s, SegmentationMethod& m);

/// \brief Settings. For IMRG/MRG a value ≤ 0 (angles, k) keeps the class default and a negative
///        threshold keeps the adaptive rule. The pcl::RegionGrowing defaults are the "looser"
///        setting of shared/data/MANIFEST.md §D (k 20, 10°, curvature 0.1, min 30), which beat
///        PCL's tutorial values (k 30, 3°, 1.0, 50) on the IGN tile.
struct SegmentationRunSettings
{
  SegmentationMethod method = SegmentationMethod::IMRG;
  int k_min = 0, k_max = 0;            ///< optimal-neighbourhood scan range; 0: class default
  double normal_angle_deg = 0.0;       ///< N_t [deg]; ≤ 0: class default
  double principal_angle_deg = 0.0;    ///< M_t [deg]; ≤ 0: class default
  double residual_threshold = -1.0;    ///< v_t [m]; < 0: adaptive
  double distance_threshold = -1.0;    ///< d_t [m]; < 0: adaptive
  double similarity_threshold = -1.0;  ///< s_t [m]; < 0: adaptive
  double volume_threshold = -1.0;      ///< V_t [-]; < 0: adaptive
  int threads = 0;                     ///< OpenMP threads; 0: default
  int min_fragment_size = -1;          ///< absorb segments under this size; < 0: class default
  SegmentationLevel level = SegmentationLevel::Objects;  ///< IMRG/MRG output stage
  std::size_t voxel_segments = 0;                        ///< VoxelGrid: wanted number of segments (> 0)

  int rg_normal_k = 20;             ///< NormalEstimationOMP k
  int rg_k = 20;                    ///< RegionGrowing k
  double rg_smoothness_deg = 10.0;  ///< RegionGrowing smoothness threshold [deg]
  double rg_curvature = 0.1;        ///< RegionGrowing curvature threshold
  int rg_min_cluster = 30;          ///< RegionGrowing min cluster size

  /// False with a one-line reason for impossible values (k_min > k_max, angles ≥ 180°, ...).
  bool
  isValid(std::string* why) const;
};

/// \brief Output of runSegmentation(). Multi-rule fields stay NaN / 0 for pcl_rg.
struct SegmentationRun
{
  SegmentationMethod method = SegmentationMethod::IMRG;
  std::vector<pcl::PointIndices> segments;
  double seconds_total = 0.0;         ///< wall time of the method (normals included for pcl_rg)
  double seconds_normals = 0.0;       ///< pcl_rg: NormalEstimationOMP
  double seconds_segmentation = 0.0;  ///< extract()
  double residual_threshold = 0.0;    ///< v_t used [m]
  double distance_threshold = 0.0;    ///< d_t used [m]
  double similarity_threshold = 0.0;  ///< s_t used [m]
  double volume_threshold = 0.0;      ///< V_t used [-]
  double spacing = 0.0, growth_radius = 0.0, volumetric_radius = 0.0;  ///< [m]
  double voxel_size = 0.0;                                             ///< VoxelGrid: edge used
  std::size_t rest_points = 0;  ///< pcl_rg: points of the "rest" segment (0: none)
  /// IMRG/MRG: segments of the other level than settings.level (planes when objects were
  /// returned and vice versa), so one run gives both.
  std::vector<pcl::PointIndices> other_level;
  /// IMRG: the class of every segment of `segments` (segmentation::ObjectClass; planes take
  /// their object's); empty for MRG, pcl_rg and the voxel grid.
  std::vector<segmentation::ObjectClass> classes;
  std::size_t linear = 0, planar = 0, volumetric = 0, invalid = 0;  ///< points per class
  /// Per input point: 0 linear, 1 planar, 2 volumetric, 255 not processed (empty for pcl_rg).
  std::vector<std::uint8_t> dimensionality;
  std::size_t segments_before_merge = 0, segments_after_merge = 0, merges = 0;
  std::size_t distance_samples = 0, volume_samples = 0;  ///< |D| and |ΔV| fed to the snooping
  std::size_t fragments_absorbed = 0;                    ///< IMRG/MRG: segments absorbed after merging
  /// IMRG/MRG: segments before merging by hull kind (degenerate: tiny, collinear, flat).
  std::size_t hulls_tiny = 0, hulls_collinear = 0, hulls_flat = 0, hulls_solid = 0;
  /// IMRG/MRG wall time per stage [s]: search structure, features, growing, merging, absorbing.
  double seconds_search = 0.0, seconds_features = 0.0, seconds_growing = 0.0, seconds_merging = 0.0,
         seconds_absorbing = 0.0;
};

/// \brief Runs settings.method on `cloud` (finite points; local coordinates).
/// \param[in] number_of_returns per point of `cloud`, its pulse's number of returns (LAS), for
///            IMRG's object classes (MultiRuleRegionGrowing::setNumberOfReturns); empty: unknown
/// \return false with a one-line reason (invalid settings, empty cloud, returns not one per
///         point, no segment found); \a run.seconds_total is set even then, so a failed
///         baseline can still be reported
bool
runSegmentation(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud,
                const SegmentationRunSettings& settings, SegmentationRun& run, std::string& error,
                const std::vector<std::uint8_t>& number_of_returns = {});

/// \brief The run's object classes (IMRG's) scored point by point against \a reference_labels:
///        evaluateClassification() of the LAS codes classCodesFromSegments() gives, as method
///        "<method> classes" with the run's time and segment count.
/// \return false with a one-line reason (not one class per segment, or the segments index
///         past the reference)
bool
evaluateRunClasses(const SegmentationRun& run, const std::vector<int>& reference_labels,
                   const SegmentationEvaluationSettings& settings, SegmentationEvaluation& result,
                   std::string& error);

}  // namespace evaluation
}  // namespace pcl_ls3d
