#include <pcl_ls3d/evaluation/segmentation_labels.h>
#include <pcl_ls3d/evaluation/segmentation_runner.h>
#include <pcl_ls3d/evaluation/voxel_baseline.h>
#include <pcl_ls3d/segmentation/multi_rule_region_growing.h>

#include <pcl/common/time.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/region_growing.h>

#include <cmath>

namespace pcl_ls3d {
namespace evaluation {

namespace {
constexpr double kDegToRad = M_PI / 180.0;

using MRG = MultiRuleRegionGrowing<pcl::PointXYZ>;

/// The run's settings on the segmenter; what is unset (≤ 0, or negative: adaptive, the
/// tools' convention) keeps the class's default.
void
configureMultiRule(const SegmentationRunSettings& s, MRG& seg)
{
  seg.setMode(s.method == SegmentationMethod::IMRG ? MRG::Mode::IMRG : MRG::Mode::MRG);
  if (s.k_min > 0 && s.k_max > 0)
    seg.setNeighbourhoodRange(s.k_min, s.k_max, seg.getNeighbourhoodRange().k_step);
  if (s.normal_angle_deg > 0.0)
    seg.setNormalAngleThreshold(s.normal_angle_deg * kDegToRad);
  if (s.principal_angle_deg > 0.0)
    seg.setPrincipalAngleThreshold(s.principal_angle_deg * kDegToRad);
  if (s.residual_threshold >= 0.0)
    seg.setResidualThreshold(s.residual_threshold);
  if (s.distance_threshold >= 0.0)
    seg.setDistanceThreshold(s.distance_threshold);
  if (s.similarity_threshold >= 0.0)
    seg.setSimilarityThreshold(s.similarity_threshold);
  if (s.volume_threshold >= 0.0)
    seg.setVolumeChangeThreshold(s.volume_threshold);
  if (s.threads > 0)
    seg.setNumberOfThreads(s.threads);
  if (s.min_fragment_size >= 0)
    seg.setMinFragmentSize(static_cast<std::size_t>(s.min_fragment_size));
  seg.setOutputLevel(s.level == SegmentationLevel::Planes ? MRG::Level::Planes : MRG::Level::Objects);
}

/// The thresholds the segmenter used, its merge figures and stage times.
void
recordMultiRuleFigures(const MRG& seg, SegmentationRun& run)
{
  run.residual_threshold = seg.getResidualThreshold();
  const auto& m = seg.getMergeReport();
  run.distance_threshold = m.distance_threshold;
  run.similarity_threshold = m.similarity_threshold;
  run.volume_threshold = m.volume_threshold;
  run.segments_before_merge = seg.getNumberOfInitialSegments();
  run.segments_after_merge = m.segments_after;
  run.merges = m.merges;
  run.hulls_tiny = m.hulls_tiny;
  run.hulls_collinear = m.hulls_collinear;
  run.hulls_flat = m.hulls_flat;
  run.hulls_solid = m.hulls_solid;
  run.fragments_absorbed = seg.getNumberOfAbsorbedFragments();
  const auto& t = seg.getStageTimes();
  run.seconds_search = t.search;
  run.seconds_features = t.features;
  run.seconds_growing = t.growing;
  run.seconds_merging = t.merging;
  run.seconds_absorbing = t.absorbing;
  run.distance_samples = m.distance_samples;
  run.volume_samples = m.volume_samples;
  run.spacing = seg.getSpacing();
  run.growth_radius = seg.getGrowthRadius();
  run.volumetric_radius = seg.getVolumetricRadius();
}

/// Each point's dimensionality class and the count per class.
void
recordDimensionality(const MRG& seg, SegmentationRun& run)
{
  using D = segmentation::Dimensionality;
  const std::vector<D> dims = seg.getDimensionality();
  run.dimensionality.reserve(dims.size());
  for (D d : dims) {
    run.dimensionality.push_back(static_cast<std::uint8_t>(d));
    switch (d) {
    case D::Linear:
      ++run.linear;
      break;
    case D::Planar:
      ++run.planar;
      break;
    case D::Volumetric:
      ++run.volumetric;
      break;
    default:
      ++run.invalid;
      break;
    }
  }
}

void
runMultiRule(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud,
             const std::vector<std::uint8_t>& number_of_returns, const SegmentationRunSettings& s,
             SegmentationRun& run)
{
  MRG seg;
  seg.setInputCloud(cloud);
  seg.setNumberOfReturns(number_of_returns);
  configureMultiRule(s, seg);
  const bool planes = s.level == SegmentationLevel::Planes;
  pcl::StopWatch watch;
  seg.extract(run.segments);
  run.seconds_segmentation = run.seconds_total = watch.getTimeSeconds();
  run.other_level = seg.getClusters(planes ? MRG::Level::Objects : MRG::Level::Planes);
  run.classes = seg.getClusterClasses(planes ? MRG::Level::Planes : MRG::Level::Objects);
  recordMultiRuleFigures(seg, run);
  recordDimensionality(seg, run);
}

void
runPclRegionGrowing(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud, const SegmentationRunSettings& s,
                    SegmentationRun& run)
{
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  pcl::StopWatch watch;
  pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> ne;
  if (s.threads > 0)
    ne.setNumberOfThreads(static_cast<unsigned>(s.threads));
  ne.setInputCloud(cloud);
  ne.setSearchMethod(tree);
  ne.setKSearch(s.rg_normal_k);
  ne.compute(*normals);
  run.seconds_normals = watch.getTimeSeconds();

  watch.reset();
  pcl::RegionGrowing<pcl::PointXYZ, pcl::Normal> rg;
  rg.setMinClusterSize(static_cast<pcl::uindex_t>(s.rg_min_cluster));
  rg.setSearchMethod(tree);
  rg.setNumberOfNeighbours(static_cast<unsigned>(s.rg_k));
  rg.setInputCloud(cloud);
  rg.setInputNormals(normals);
  rg.setSmoothnessThreshold(static_cast<float>(s.rg_smoothness_deg * kDegToRad));
  rg.setCurvatureThreshold(static_cast<float>(s.rg_curvature));
  rg.extract(run.segments);
  // Points in no cluster (clusters under the minimum size, or never reached) form one "rest"
  // segment: they are kept, not thrown away, so the object-based rules judge them like any
  // other segment instead of counting them only as missed points.
  std::vector<char> used(cloud->size(), 0);
  for (const auto& c : run.segments)
    for (const auto i : c.indices)
      used[static_cast<std::size_t>(i)] = 1;
  pcl::PointIndices rest;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (!used[i])
      rest.indices.push_back(static_cast<int>(i));
  run.rest_points = rest.indices.size();
  if (!rest.indices.empty())
    run.segments.push_back(std::move(rest));
  run.seconds_segmentation = watch.getTimeSeconds();
  run.seconds_total = run.seconds_normals + run.seconds_segmentation;
  run.segments_before_merge = run.segments_after_merge = run.segments.size();
  const double nan = std::nan("");
  run.residual_threshold = run.distance_threshold = run.similarity_threshold = run.volume_threshold =
      run.spacing = run.growth_radius = run.volumetric_radius = nan;
}
void
runVoxelGrid(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud, const SegmentationRunSettings& s,
             SegmentationRun& run)
{
  pcl::StopWatch watch;
  run.segments = voxelSegmentsWithCount(*cloud, s.voxel_segments, run.voxel_size);
  run.seconds_segmentation = run.seconds_total = watch.getTimeSeconds();
  run.segments_before_merge = run.segments_after_merge = run.segments.size();
  const double nan = std::nan("");
  run.residual_threshold = run.distance_threshold = run.similarity_threshold = run.volume_threshold =
      run.spacing = run.growth_radius = run.volumetric_radius = nan;
}
}  // namespace

std::string
toString(SegmentationMethod m)
{
  switch (m) {
  case SegmentationMethod::IMRG:
    return "imrg";
  case SegmentationMethod::MRG:
    return "mrg";
  case SegmentationMethod::VoxelGrid:
    return "voxel";
  default:
    return "pcl_rg";
  }
}

bool
parseSegmentationMethod(const std::string& s, SegmentationMethod& m)
{
  for (auto c : {SegmentationMethod::IMRG, SegmentationMethod::MRG, SegmentationMethod::PclRegionGrowing,
                 SegmentationMethod::VoxelGrid})
    if (s == toString(c)) {
      m = c;
      return true;
    }
  return false;
}

bool
SegmentationRunSettings::isValid(std::string* why) const
{
  auto fail = [why](const std::string& msg) {
    if (why)
      *why = msg;
    return false;
  };
  if ((k_min > 0) != (k_max > 0) || (k_min > 0 && (k_min < 3 || k_max < k_min || k_max > 65535)))
    return fail("neighbourhood range needs 3 <= kmin <= kmax <= 65535 (got " + std::to_string(k_min) + "," +
                std::to_string(k_max) + ")");
  if (!(normal_angle_deg < 180.0) || !(principal_angle_deg < 180.0))
    return fail("angle thresholds must be below 180 degrees");
  for (double t : {residual_threshold, distance_threshold, similarity_threshold, volume_threshold})
    if (std::isnan(t))
      return fail("thresholds must be numbers (negative = adaptive)");
  if (rg_normal_k < 3 || rg_k < 1 || rg_min_cluster < 1 || !(rg_smoothness_deg > 0.0) ||
      !(rg_curvature > 0.0))
    return fail("invalid pcl::RegionGrowing settings");
  if (threads < 0)
    return fail("threads must be >= 0");
  if (method == SegmentationMethod::VoxelGrid && voxel_segments == 0)
    return fail("the voxel baseline needs a segment count > 0");
  return true;
}

bool
runSegmentation(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud,
                const SegmentationRunSettings& settings, SegmentationRun& run, std::string& error,
                const std::vector<std::uint8_t>& number_of_returns)
{
  run = SegmentationRun{};
  run.method = settings.method;
  if (!settings.isValid(&error))
    return false;
  if (!cloud || cloud->empty()) {
    error = "empty cloud";
    return false;
  }
  if (!number_of_returns.empty() && number_of_returns.size() != cloud->size()) {
    error = std::to_string(number_of_returns.size()) + " numbers of returns for " +
            std::to_string(cloud->size()) + " points";
    return false;
  }
  if (settings.method == SegmentationMethod::PclRegionGrowing)
    runPclRegionGrowing(cloud, settings, run);
  else if (settings.method == SegmentationMethod::VoxelGrid)
    runVoxelGrid(cloud, settings, run);
  else
    runMultiRule(cloud, number_of_returns, settings, run);
  if (run.segments.empty()) {
    error = toString(settings.method) + " found no segment";
    return false;
  }
  return true;
}

bool
evaluateRunClasses(const SegmentationRun& run, const std::vector<int>& reference_labels,
                   const SegmentationEvaluationSettings& settings, SegmentationEvaluation& result,
                   std::string& error)
{
  if (run.classes.size() != run.segments.size()) {
    error = std::to_string(run.classes.size()) + " classes for " + std::to_string(run.segments.size()) +
            " segments";
    return false;
  }
  result = SegmentationEvaluation();
  result.method = toString(run.method) + " classes";
  result.seconds = run.seconds_total;
  result.segments = run.segments.size();
  return evaluateClassification(classCodesFromSegments(run.segments, run.classes, reference_labels.size()),
                                reference_labels, settings, result, error);
}

}  // namespace evaluation
}  // namespace pcl_ls3d
