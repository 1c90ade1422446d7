#pragma once
/// \file multi_rule_region_growing.h
/// \brief Improved multi-rule region growing (IMRG, Wang et al. 2021) as a pcl::PCLBase subclass
///        used like pcl::RegionGrowing.

#include <pcl_ls3d/segmentation/dimensionality_features.h>
#include <pcl_ls3d/segmentation/fragment_absorption.h>
#include <pcl_ls3d/segmentation/ground_filter.h>
#include <pcl_ls3d/segmentation/object_assembly.h>
#include <pcl_ls3d/segmentation/object_classes.h>
#include <pcl_ls3d/segmentation/roof_cover.h>
#include <pcl_ls3d/segmentation/rule_growing.h>
#include <pcl_ls3d/segmentation/segment_merging.h>
#include <pcl_ls3d/segmentation/terrain_contact.h>

#include <pcl/PointIndices.h>
#include <pcl/pcl_base.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/search.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pcl_ls3d {

/// \brief Multi-factor segmentation by improved multi-rule region growing (IMRG).
///
/// Pipeline of extract() (Wang et al. 2021, §2–3):
///  1. one k-NN query (k_max) per point; the optimal neighbourhood k minimises the
///     eigen-entropy (Weinmann et al.); from λ1 ≥ λ2 ≥ λ3 of its covariance:
///     a1D = (√λ1−√λ2)/√λ1, a2D = (√λ2−√λ3)/√λ1, a3D = √λ3/√λ1; the argmax puts the point in
///     the linear, planar or volumetric set. Normal (λ3 eigenvector), principal direction
///     (λ1 eigenvector) and the plane-fitting residual √λ3 (RMS distance to the LS plane, metres)
///     come from the same neighbourhood.
///  2. growing per set, over the k-NN graph (setNumberOfNeighbours) restricted to the set:
///     linear: principal directions within M_t and distance ≤ growth radius;
///     planar: normals within N_t, distance ≤ growth radius and (an addition) the neighbour
///     within growth radius × sin N_t of the tangent plane (rule_growing.h);
///     volumetric: Euclidean connectivity within the volumetric radius (vegetation has no
///     stable normal or direction, so only proximity is meaningful; the radius follows the
///     local point spacing so it adapts to density).
///  3. IMRG seed condition (§3.1): a planar point propagates growth only if its residual is
///     below v_t; v_t defaults to the median residual of the linear set.
///  4. merging (§3.2, Fig. 8), smallest segment first, into its nearest segment by convex-hull
///     contour distance, when distance ≤ d_t, |R_i − R_j| ≤ s_t and ΔV = (V_j'' − V_j')/V_i ≤ V_t
///     (R = mean point residual of a segment, eq. 1; ΔV eq. 2). d_t, V_t: Baarda data snooping
///     (backward elimination, α = 0.001) then max of the rest (V_t on ∛ΔV); s_t: smallest gap
///     of 3 k-means centres of segment residuals. Flat or collinear segments have hull volume 0;
///     ΔV's denominator is floored at n_i·spacing³. See segment_merging.h and segment_hull.h.
///  5. fragments under setMinFragmentSize() points join their most linked neighbour
///     (fragment_absorption.h).
///  6. object assembly (an addition, IMRG mode): a progressive morphological ground filter
///     marks the ground, each segment gets a kind (ground, solid, wall, rough, linear) and
///     touching segments of kinds that belong together join into whole objects: a building
///     (roof planes, walls, edge lines, chimneys), a tree group, the ground, a wire span
///     (object_assembly.h); fragments are absorbed once more, through touching links only
///     (no longer than the growth radius, none from a rough fragment into the ground:
///     absorptionContact), so a bush on a lawn stays its own object.
///  7. object classes (an addition, with the assembly): each object is ground, building,
///     vegetation, wire, pole, car or unclassified by the kinds of its segments, its height
///     above the terrain and its size (object_classes.h).
///  8. points by position (an addition, with the classes; AssemblySettings
///     terrain_return_multiple, claim_under_roofs): vegetation and car points the ground
///     filter keeps no higher than 3 ground residuals above the terrain plane join the ground
///     object beside them (terrain_contact.h), then vegetation points under a building's roof
///     join it (roof_cover.h: facade scatter the growth put into the crowns in front).
///     Classes are not recomputed; an object may lose points to them (a few-point remnant
///     stays an object).
///     A plane takes the class of the object holding most of its points
///     (getClusterClasses()).
/// Two levels come out of one extract() (setOutputLevel(), getClusters()): Level::Planes, the
/// segments of step 2–3 (the planes of the paper's Table 1: roof planes, facades, ground
/// pieces), and Level::Objects, the result of steps 4–8 (default).
///
/// Plain MRG (the paper's comparison) = setMode(Mode::MRG): no seed condition, distance-only
/// merging, no object assembly. Every adaptive threshold can be overridden by its setter and
/// read after extract(); useAdaptiveThresholds() restores the adaptive rules.
///
/// Used in place of pcl::RegionGrowing (PCL 1.13), the differences are:
///  - Normals are optional. Without setInputNormals() the class uses its own (the λ3
///    eigenvector of each point's optimal neighbourhood, computed for the dimensionality
///    features anyway) and segments; pcl::RegionGrowing returns no segment without normals.
///    Given normals replace the computed ones in the planar rule only.
///  - Invalid settings are refused as pcl::RegionGrowing refuses them: extract() logs one
///    PCL_ERROR line and returns no segment (getNumberOfNeighbours() < 1, a residual threshold
///    ≤ 0 — PCL's residual test refuses it too —, a negative or non-finite d_t, s_t or V_t,
///    normals or numbers of returns of another size than the cloud, fewer finite points than
///    the smallest neighbourhood).
///  - setResidualTestFlag() is the IMRG seed condition (a point grows its segment only when its
///    plane-fit residual is below v_t), on by default (IMRG mode); there is no curvature test
///    and setSmoothnessThreshold() is N_t (setNormalAngleThreshold()), 10° by default.
///  - getSegmentFromPoint() before extract() runs the segmentation itself, as PCL's does.
///  - Output is whole objects by default (Level::Objects, after merging); Level::Planes is
///    closest to pcl::RegionGrowing's smooth regions. The minimum cluster size defaults to 1
///    (pcl::RegionGrowing: 1 as well) and fragments under 30 points join a neighbour instead of
///    being dropped (setMinFragmentSize()).
template <typename PointT, typename NormalT = pcl::Normal>
class MultiRuleRegionGrowing : public pcl::PCLBase<PointT>
{
public:
  using Ptr = std::shared_ptr<MultiRuleRegionGrowing<PointT, NormalT>>;
  using ConstPtr = std::shared_ptr<const MultiRuleRegionGrowing<PointT, NormalT>>;
  using KdTree = pcl::search::Search<PointT>;
  using KdTreePtr = typename KdTree::Ptr;
  using Normal = pcl::PointCloud<NormalT>;
  using NormalPtr = typename Normal::Ptr;
  using PointCloud = pcl::PointCloud<PointT>;
  using Dimensionality = segmentation::Dimensionality;
  using PointFeatures = segmentation::PointFeatures;
  using MergeRule = segmentation::MergeRule;

  using pcl::PCLBase<PointT>::input_;
  using pcl::PCLBase<PointT>::indices_;
  using pcl::PCLBase<PointT>::initCompute;
  using pcl::PCLBase<PointT>::deinitCompute;

  /// \brief IMRG (seed condition + distance/similarity/volume merging) or plain MRG.
  enum class Mode
  {
    IMRG,
    MRG
  };

  /// \brief What extract() returns: the planes of the growing stage (the paper's Table 1,
  ///        before merging) or whole objects (after merging). Both are kept after extract().
  enum class Level
  {
    Planes,
    Objects
  };

  /// \brief Defaults: k = 10..100 step 10, 16 graph neighbours, M_t = 15°, N_t = 10°, IMRG mode.
  MultiRuleRegionGrowing();
  ~MultiRuleRegionGrowing() override;

  /// \brief Class name for messages.
  std::string
  getClassName() const
  {
    return "MultiRuleRegionGrowing";
  }

  // ---- neighbourhood and features --------------------------------------------------------
  /// \brief Scan k = k_min, k_min + step, ..., k_max for the minimal eigen-entropy.
  void
  setNeighbourhoodRange(int k_min, int k_max, int k_step = 10);
  /// \brief Fixed-k mode: every point uses exactly k neighbours (including itself).
  void
  setFixedNeighbourhood(int k)
  {
    setNeighbourhoodRange(k, k, 1);
  }
  const segmentation::NeighbourhoodSettings&
  getNeighbourhoodRange() const
  {
    return nbh_;
  }
  /// \brief Size of the k-NN graph used for growing (default 16).
  void
  setNumberOfNeighbours(int k)
  {
    grow_.graph_k = k;
  }
  int
  getNumberOfNeighbours() const
  {
    return grow_.graph_k;
  }
  /// \brief Threads for the per-point stages (0: OpenMP default).
  void
  setNumberOfThreads(int n)
  {
    threads_ = n;
  }

  // ---- growing rules -----------------------------------------------------------------------
  /// \brief M_t [rad]: max angle between principal directions of linear points (default 15°).
  void
  setPrincipalAngleThreshold(double rad)
  {
    grow_.principal_angle = rad;
  }
  double
  getPrincipalAngleThreshold() const
  {
    return grow_.principal_angle;
  }
  /// \brief N_t [rad]: max angle between normals of planar points (default 10°).
  void
  setNormalAngleThreshold(double rad)
  {
    grow_.normal_angle = rad;
  }
  double
  getNormalAngleThreshold() const
  {
    return grow_.normal_angle;
  }
  /// \brief Max neighbour distance [m] for linear/planar growth; ≤ 0: auto (see getSpacing()).
  void
  setGrowthRadius(double r)
  {
    user_growth_radius_ = r;
  }
  double
  getGrowthRadius() const
  {
    return grow_.growth_radius;
  }
  /// \brief Connectivity radius [m] of volumetric growth; ≤ 0: auto (see getSpacing()).
  void
  setVolumetricRadius(double r)
  {
    user_volumetric_radius_ = r;
  }
  double
  getVolumetricRadius() const
  {
    return grow_.volumetric_radius;
  }
  /// \brief Local spacing scale [m] of the last extract(): median distance to the k_min-th
  ///        neighbour. Auto growth radius = 2 × spacing, auto volumetric radius = 1 × spacing.
  double
  getSpacing() const
  {
    return spacing_;
  }

  // ---- IMRG seed condition -----------------------------------------------------------------
  /// \brief Enable/disable the planar seed condition (IMRG §3.1).
  void
  setUseSeedCondition(bool on)
  {
    grow_.use_seed_condition = on;
  }
  bool
  getUseSeedCondition() const
  {
    return grow_.use_seed_condition;
  }
  /// \brief pcl::RegionGrowing's name of the seed condition (its residual test).
  void
  setResidualTestFlag(bool on)
  {
    setUseSeedCondition(on);
  }
  bool
  getResidualTestFlag() const
  {
    return getUseSeedCondition();
  }
  /// \brief v_t [m], fixed; must be > 0 (extract() refuses anything else, as
  ///        pcl::RegionGrowing's residual test does). Default: adaptive, the median residual of
  ///        the linear set (useAdaptiveThresholds()).
  void
  setResidualThreshold(double v)
  {
    user_residual_threshold_ = v;
  }
  /// \brief v_t used by the last extract() (NaN before).
  double
  getResidualThreshold() const
  {
    return grow_.residual_threshold;
  }
  /// \brief pcl::RegionGrowing's name of N_t [rad] (setNormalAngleThreshold()).
  void
  setSmoothnessThreshold(double rad)
  {
    setNormalAngleThreshold(rad);
  }
  double
  getSmoothnessThreshold() const
  {
    return getNormalAngleThreshold();
  }

  // ---- merging -----------------------------------------------------------------------------
  void
  setMergeRule(MergeRule rule)
  {
    merge_.rule = rule;
  }
  MergeRule
  getMergeRule() const
  {
    return merge_.rule;
  }
  /// \brief Mode::IMRG: seed condition, full merge rule, object assembly; Mode::MRG: none of
  ///        them (distance-only merging).
  void
  setMode(Mode mode);
  /// \brief d_t [m], fixed, ≥ 0 (default adaptive: Baarda snooping over nearest-segment
  ///        distances).
  void
  setDistanceThreshold(double d)
  {
    user_distance_threshold_ = d;
  }
  /// \brief s_t [m], fixed, ≥ 0 (default adaptive: smallest gap of 3 k-means centres of R_i).
  void
  setSimilarityThreshold(double s)
  {
    user_similarity_threshold_ = s;
  }
  /// \brief V_t, fixed, ≥ 0 (default adaptive: Baarda snooping over candidate ΔV).
  void
  setVolumeChangeThreshold(double v)
  {
    user_volume_threshold_ = v;
  }
  /// \brief Back to the adaptive rules for v_t, d_t, s_t and V_t (the default).
  void
  useAdaptiveThresholds()
  {
    user_residual_threshold_ = user_distance_threshold_ = user_similarity_threshold_ =
        user_volume_threshold_ = std::nullopt;
  }
  /// \brief Significance α of each w-test in the data snooping (default 0.001).
  void
  setSnoopingSignificance(double alpha)
  {
    merge_.alpha = alpha;
  }
  /// \brief Thresholds actually used by the last extract() and merge statistics.
  const segmentation::MergeReport&
  getMergeReport() const
  {
    return merge_report_;
  }
  double
  getDistanceThreshold() const
  {
    return merge_report_.distance_threshold;
  }
  double
  getSimilarityThreshold() const
  {
    return merge_report_.similarity_threshold;
  }
  double
  getVolumeChangeThreshold() const
  {
    return merge_report_.volume_threshold;
  }

  // ---- fragment absorption (after merging; see segmentation::absorbFragments) -------------
  /// \brief Segments under \a n points after merging join the adjacent segment sharing the most
  ///        k-NN graph links (default 30; 0 or 1: off, the paper's output). Not a filter:
  ///        no point is lost. 30 = pcl::RegionGrowing's usual minimum cluster size.
  void
  setMinFragmentSize(std::size_t n)
  {
    min_fragment_size_ = n;
  }
  std::size_t
  getMinFragmentSize() const
  {
    return min_fragment_size_;
  }
  /// \brief Number of segments absorbed in the last extract() (both absorption passes).
  std::size_t
  getNumberOfAbsorbedFragments() const
  {
    return absorbed_fragments_;
  }

  // ---- object assembly (object level; see segmentation::assembleObjects) -------------------
  /// \brief Join the merged segments into whole objects (default on; Mode::MRG turns it off).
  void
  setObjectAssembly(bool on)
  {
    assemble_objects_ = on;
  }
  bool
  getObjectAssembly() const
  {
    return assemble_objects_;
  }
  /// \brief Rules of the assembly (kinds, links); see segmentation::AssemblySettings.
  void
  setAssemblySettings(const segmentation::AssemblySettings& s)
  {
    assembly_ = s;
  }
  const segmentation::AssemblySettings&
  getAssemblySettings() const
  {
    return assembly_;
  }
  /// \brief Largest building width [m] the ground filter must remove (default 60).
  void
  setMaxObjectWidth(double w)
  {
    ground_filter_.max_window = w;
  }
  double
  getMaxObjectWidth() const
  {
    return ground_filter_.max_window;
  }
  /// \brief Segments per kind and objects of the last extract().
  const segmentation::AssemblyReport&
  getAssemblyReport() const
  {
    return assembly_report_;
  }
  /// \brief Thresholds of the object classes (heights, car and building sizes; metres).
  void
  setObjectClassSettings(const segmentation::ObjectClassSettings& s)
  {
    classes_ = s;
  }
  const segmentation::ObjectClassSettings&
  getObjectClassSettings() const
  {
    return classes_;
  }
  /// \brief Class of every cluster of getClusters(\a level) of the last extract() (a plane: the
  ///        class of the object holding most of its points); empty without the object assembly
  ///        (Mode::MRG) or when extract() failed.
  const std::vector<segmentation::ObjectClass>&
  getClusterClasses(Level level) const
  {
    return level == Level::Planes ? plane_classes_ : object_classes_;
  }

  /// \brief Wall time [s] of each stage of the last extract().
  struct StageTimes
  {
    double search = 0.0;      ///< checks, local coordinates, search-structure build
    double features = 0.0;    ///< k_max-NN query per point, eigen-entropy scan, features, graph
    double growing = 0.0;     ///< v_t and rule-based region growing
    double merging = 0.0;     ///< hulls, d_t / s_t / V_t, merge loop (§3.2)
    double absorbing = 0.0;   ///< fragment absorption
    double assembling = 0.0;  ///< ground filter, segment kinds, object assembly
    double total = 0.0;       ///< the whole extract()
  };
  const StageTimes&
  getStageTimes() const
  {
    return stage_times_;
  }

  // ---- output filtering (as pcl::RegionGrowing) ---------------------------------------------
  void
  setMinClusterSize(pcl::uindex_t n)
  {
    min_cluster_size_ = n;
  }
  pcl::uindex_t
  getMinClusterSize() const
  {
    return min_cluster_size_;
  }
  void
  setMaxClusterSize(pcl::uindex_t n)
  {
    max_cluster_size_ = n;
  }
  pcl::uindex_t
  getMaxClusterSize() const
  {
    return max_cluster_size_;
  }

  // ---- inputs -------------------------------------------------------------------------------
  /// \brief Search method (a pcl::search::KdTree is created when none is given). extract()
  ///        sets its input and queries it from several OpenMP threads at once (const queries,
  ///        as pcl::NormalEstimationOMP does), one k_max-NN query per point.
  void
  setSearchMethod(const KdTreePtr& tree)
  {
    search_ = tree;
  }
  KdTreePtr
  getSearchMethod() const
  {
    return search_;
  }
  /// \brief Optional normals used by the planar rule instead of the computed ones.
  void
  setInputNormals(const NormalPtr& normals)
  {
    normals_ = normals;
  }
  NormalPtr
  getInputNormals() const
  {
    return normals_;
  }
  /// \brief Optional: the number of returns of each input point's pulse (LAS NumberOfReturns),
  ///        one per point of the input cloud (not per index). Only the object classes use it: a
  ///        car-sized rough object with at most 20 % of its points from pulses with several
  ///        returns is a car, not a shrub (ObjectClassSettings::car_max_multiple_return_share).
  ///        Empty (the default), or all at most 1 over the whole input (data that do not record
  ///        returns, segmentation::recordsReturns()): returns unknown. Another size: extract()
  ///        fails.
  void
  setNumberOfReturns(std::vector<std::uint8_t> returns)
  {
    returns_ = std::move(returns);
  }
  const std::vector<std::uint8_t>&
  getNumberOfReturns() const
  {
    return returns_;
  }

  // ---- run and results -----------------------------------------------------------------------
  /// \brief Level returned by extract() and used by the per-point getters (default Objects).
  void
  setOutputLevel(Level level)
  {
    level_ = level;
  }
  Level
  getOutputLevel() const
  {
    return level_;
  }
  /// \brief Segment the cloud. On bad input logs PCL_ERROR and returns no clusters.
  void
  extract(std::vector<pcl::PointIndices>& clusters);
  /// \brief Segments of either level from the last extract() (min/max cluster size applied).
  const std::vector<pcl::PointIndices>&
  getClusters(Level level) const
  {
    return level == Level::Planes ? plane_clusters_ : object_clusters_;
  }
  /// \brief The cluster containing the cloud point \a index (empty if none). Before any
  ///        extract() (or after one that gave no segment) it runs extract() first, as
  ///        pcl::RegionGrowing::getSegmentFromPoint does.
  void
  getSegmentFromPoint(pcl::index_t index, pcl::PointIndices& cluster);
  /// \brief Input cloud with one random colour per cluster; other points white.
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr
  getColoredCloud() const;
  /// \brief Per input-cloud point: its dimensionality (Invalid if not processed).
  std::vector<Dimensionality>
  getDimensionality() const;
  /// \brief Features of input-cloud point \a index; false if it was not processed.
  bool
  getPointFeatures(pcl::index_t index, PointFeatures& features) const;
  /// \brief Per input-cloud point: index of its returned cluster, −1 if none.
  std::vector<int>
  getPointLabels() const;
  /// \brief Number of segments before merging (all sizes).
  std::size_t
  getNumberOfInitialSegments() const
  {
    return initial_segments_;
  }

protected:
  /// Empties the results, reports and stage times of the previous run.
  void
  resetRunState();
  bool
  prepareForSegmentation();
  /// Why the user's thresholds cannot be used ("" when they can); fills merge_'s thresholds.
  std::string
  checkThresholds();
  bool
  computeFeatures();
  void
  growSegments();
  /// Plane level: fragments in plane_of_ join their most-linked plane, on-plane links only.
  void
  absorbPlaneFragments();
  void
  mergeSegments();
  void
  assembleObjects();
  /// Clusters and classes of both levels from plane_of_ and segment_of_.
  void
  assembleLevelClusters();
  /// Per position: 1 if the point's pulse had several returns; empty when returns are unknown.
  std::vector<char>
  multipleReturnFlags() const;
  /// Step 8: vegetation (and car) points on the terrain join the ground, vegetation points under
  /// a roof the building.
  void
  assignPointsByPosition(const std::vector<char>& ground, const segmentation::AssemblySettings& settings);
  /// Clusters (cloud indices) of per-position \a labels, min/max cluster size applied.
  void
  assembleRegions(const std::vector<int>& labels, std::vector<pcl::PointIndices>& clusters,
                  std::vector<int>& cluster_of) const;
  /// Per cluster: the class of the object holding most of its points (object_class_).
  std::vector<segmentation::ObjectClass>
  clusterClasses(const std::vector<pcl::PointIndices>& clusters) const;

  // settings
  segmentation::NeighbourhoodSettings nbh_;
  segmentation::GrowingSettings grow_;
  segmentation::MergeSettings merge_;
  double user_growth_radius_ = 0.0;
  double user_volumetric_radius_ = 0.0;
  std::optional<double> user_residual_threshold_;  ///< v_t set by the user (none: adaptive)
  std::optional<double> user_distance_threshold_, user_similarity_threshold_,
      user_volume_threshold_;  ///< d_t, s_t, V_t set by the user (none: adaptive)
  pcl::uindex_t min_cluster_size_ = 1;
  pcl::uindex_t max_cluster_size_ = std::numeric_limits<pcl::uindex_t>::max();
  int threads_ = 0;
  KdTreePtr search_;
  NormalPtr normals_;
  std::vector<std::uint8_t> returns_;  ///< per input point; empty: unknown

  // state of the last run; "position" = index into valid_indices_
  std::vector<int> valid_indices_;       ///< cloud indices processed (finite, in indices_)
  std::vector<int> position_of_;         ///< cloud index -> position or -1
  std::vector<Eigen::Vector3f> points_;  ///< coordinates minus origin_, per position
  Eigen::Vector3f origin_ = Eigen::Vector3f::Zero();
  std::vector<PointFeatures> features_;                    ///< per position
  std::vector<int> graph_;                                 ///< k-NN graph, graph_k positions per position
  std::vector<int> segment_of_;                            ///< per position: segment id or -1
  std::vector<int> plane_of_;                              ///< per position: plane-level segment or -1
  std::vector<pcl::PointIndices> plane_clusters_;          ///< plane level (cloud indices)
  std::vector<pcl::PointIndices> object_clusters_;         ///< object level (cloud indices)
  std::vector<int> plane_cluster_of_, object_cluster_of_;  ///< per position: cluster or -1
  Level level_ = Level::Objects;
  segmentation::MergeReport merge_report_;
  double spacing_ = 0.0;
  std::size_t initial_segments_ = 0;
  std::size_t min_fragment_size_ = 30;
  std::size_t absorbed_fragments_ = 0;
  bool assemble_objects_ = true;
  segmentation::AssemblySettings assembly_;
  segmentation::GroundFilterSettings ground_filter_;
  segmentation::AssemblyReport assembly_report_;
  segmentation::ObjectClassSettings classes_;
  std::vector<segmentation::ObjectClass> object_class_;                    ///< per object label (segment_of_)
  std::vector<segmentation::ObjectClass> plane_classes_, object_classes_;  ///< per cluster
  StageTimes stage_times_;
};

}  // namespace pcl_ls3d

#ifdef PCL_NO_PRECOMPILE
#include <pcl_ls3d/segmentation/impl/multi_rule_region_growing.hpp>
#endif
