#pragma once
/// \file impl/multi_rule_region_growing.hpp
/// \brief Template members of pcl_ls3d::MultiRuleRegionGrowing.

#include <pcl_ls3d/search/flann_kd_tree.h>
#include <pcl_ls3d/segmentation/adaptive_thresholds.h>
#include <pcl_ls3d/segmentation/multi_rule_region_growing.h>
#include <pcl_ls3d/stats/descriptive.h>

#include <pcl/common/point_tests.h>
#include <pcl/common/time.h>
#include <pcl/console/print.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <utility>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl_ls3d {

// Out of line so that PCLBase<T>'s members are instantiated here, in src/, for custom T.
template <typename PointT, typename NormalT>
MultiRuleRegionGrowing<PointT, NormalT>::MultiRuleRegionGrowing() = default;

template <typename PointT, typename NormalT>
MultiRuleRegionGrowing<PointT, NormalT>::~MultiRuleRegionGrowing() = default;

template <typename PointT, typename NormalT>
void
MultiRuleRegionGrowing<PointT, NormalT>::setNeighbourhoodRange(int k_min, int k_max, int k_step)
{
  nbh_.k_min = k_min;
  nbh_.k_max = k_max;
  nbh_.k_step = k_step;
}

template <typename PointT, typename NormalT>
void
MultiRuleRegionGrowing<PointT, NormalT>::setMode(Mode mode)
{
  grow_.use_seed_condition = (mode == Mode::IMRG);
  assemble_objects_ = (mode == Mode::IMRG);
  merge_.rule = (mode == Mode::IMRG) ? MergeRule::DistanceSimilarityVolume : MergeRule::DistanceOnly;
}

template <typename PointT, typename NormalT>
void
MultiRuleRegionGrowing<PointT, NormalT>::extract(std::vector<pcl::PointIndices>& clusters)
{
  clusters.clear();
  resetRunState();

  pcl::StopWatch watch;
  double last = 0.0;
  const auto lap = [&watch, &last](double& stage) {
    const double now = watch.getTimeSeconds();
    stage = now - last;
    last = now;
  };
  if (!initCompute())
    return;
  if (!prepareForSegmentation()) {
    deinitCompute();
    return;
  }
  lap(stage_times_.search);
  if (!computeFeatures()) {
    deinitCompute();
    return;
  }
  lap(stage_times_.features);
  growSegments();
  plane_of_ = segment_of_;
  absorbPlaneFragments();
  lap(stage_times_.growing);
  mergeSegments();
  lap(stage_times_.merging);
  if (min_fragment_size_ > 1)
    absorbed_fragments_ =
        segmentation::absorbFragments(graph_, grow_.graph_k, segment_of_, min_fragment_size_);
  lap(stage_times_.absorbing);
  if (assemble_objects_)
    assembleObjects();
  lap(stage_times_.assembling);
  assembleLevelClusters();
  clusters = getClusters(level_);
  stage_times_.total = watch.getTimeSeconds();
  PCL_DEBUG("[pcl_ls3d::%s::extract] %zu points: search %.2f s, features %.2f s, growing %.2f s, "
            "merging %.2f s, absorbing %.2f s; %zu -> %zu segments (%zu fragments absorbed).\n",
            getClassName().c_str(), points_.size(), stage_times_.search, stage_times_.features,
            stage_times_.growing, stage_times_.merging, stage_times_.absorbing, initial_segments_,
            object_clusters_.size(), absorbed_fragments_);
  deinitCompute();
}

template <typename PointT, typename NormalT>
void
MultiRuleRegionGrowing<PointT, NormalT>::resetRunState()
{
  plane_clusters_.clear();
  object_clusters_.clear();
  plane_cluster_of_.clear();
  object_cluster_of_.clear();
  object_class_.clear();
  plane_classes_.clear();
  object_classes_.clear();
  features_.clear();
  segment_of_.clear();
  plane_of_.clear();
  merge_report_ = segmentation::MergeReport{};
  grow_.residual_threshold = std::numeric_limits<double>::quiet_NaN();
  initial_segments_ = 0;
  absorbed_fragments_ = 0;
  assembly_report_ = segmentation::AssemblyReport{};
  stage_times_ = StageTimes{};
}

template <typename PointT, typename NormalT>
void
MultiRuleRegionGrowing<PointT, NormalT>::absorbPlaneFragments()
{
  // The plane level keeps the grown planes; points that the seed condition left in fragments
  // (residual above v_t: they join a plane but do not grow it) join their most-linked plane,
  // counting only links p -> q where p lies on q's tangent plane within what the planar rule
  // allows over one growth step (growth radius x sin N_t) and, between two planar points, the
  // normals agree within N_t; volumetric pairs always count. A fragment of a sparse wall does
  // not join the roof it touches at the eave, nor a fragment of one roof plane the plane
  // across the ridge.
  if (min_fragment_size_ <= 1)
    return;
  const double tol = grow_.growth_radius * std::sin(grow_.normal_angle);
  const double cos_nt = std::cos(grow_.normal_angle);
  const auto on_plane = [this, tol, cos_nt](int p, int q) {
    const auto& fp = features_[static_cast<std::size_t>(p)];
    const auto& fq = features_[static_cast<std::size_t>(q)];
    if (fp.dimensionality == Dimensionality::Volumetric && fq.dimensionality == Dimensionality::Volumetric)
      return true;
    const Eigen::Vector3f d = points_[static_cast<std::size_t>(p)] - points_[static_cast<std::size_t>(q)];
    if (std::abs(d.dot(fq.normal)) > tol)
      return false;
    return fp.dimensionality != Dimensionality::Planar || fq.dimensionality != Dimensionality::Planar ||
           std::abs(fp.normal.dot(fq.normal)) >= cos_nt;
  };
  segmentation::absorbFragments(graph_, grow_.graph_k, plane_of_, min_fragment_size_, on_plane);
}

template <typename PointT, typename NormalT>
void
MultiRuleRegionGrowing<PointT, NormalT>::assembleLevelClusters()
{
  assembleRegions(plane_of_, plane_clusters_, plane_cluster_of_);
  assembleRegions(segment_of_, object_clusters_, object_cluster_of_);
  if (!object_class_.empty()) {
    plane_classes_ = clusterClasses(plane_clusters_);
    object_classes_ = clusterClasses(object_clusters_);
  }
}

template <typename PointT, typename NormalT>
bool
MultiRuleRegionGrowing<PointT, NormalT>::prepareForSegmentation()
{
  const std::string cls = getClassName();
  const char* name = cls.c_str();
  if (!input_ || input_->empty()) {
    PCL_ERROR("[pcl_ls3d::%s::extract] Input cloud is empty.\n", name);
    return false;
  }
  if (nbh_.k_min < 3 || nbh_.k_max < nbh_.k_min || nbh_.k_step < 1 || nbh_.k_max > 65535) {
    PCL_ERROR("[pcl_ls3d::%s::extract] Invalid neighbourhood range k = %d..%d step %d "
              "(need 3 <= k_min <= k_max <= 65535, step >= 1).\n",
              name, nbh_.k_min, nbh_.k_max, nbh_.k_step);
    return false;
  }
  if (grow_.graph_k < 1 || !(grow_.principal_angle > 0.0) || !(grow_.normal_angle > 0.0) ||
      !std::isfinite(user_growth_radius_) || !std::isfinite(user_volumetric_radius_)) {
    PCL_ERROR("[pcl_ls3d::%s::extract] Invalid growing settings (neighbours %d, angles must be "
              "> 0, radii finite).\n",
              name, grow_.graph_k);
    return false;
  }
  if (const std::string why = checkThresholds(); !why.empty()) {
    PCL_ERROR("[pcl_ls3d::%s::extract] %s\n", name, why.c_str());
    return false;
  }
  if (normals_ && normals_->size() != input_->size()) {
    PCL_ERROR("[pcl_ls3d::%s::extract] %zu normals for %zu points.\n", name,
              static_cast<std::size_t>(normals_->size()), static_cast<std::size_t>(input_->size()));
    return false;
  }
  if (!returns_.empty() && returns_.size() != input_->size()) {
    PCL_ERROR("[pcl_ls3d::%s::extract] %zu numbers of returns for %zu points.\n", name, returns_.size(),
              static_cast<std::size_t>(input_->size()));
    return false;
  }

  valid_indices_.clear();
  position_of_.assign(input_->size(), -1);
  for (const auto i : *indices_) {
    if (i < 0 || static_cast<std::size_t>(i) >= input_->size() || position_of_[i] >= 0 ||
        !pcl::isXYZFinite((*input_)[i]))
      continue;
    position_of_[i] = static_cast<int>(valid_indices_.size());
    valid_indices_.push_back(static_cast<int>(i));
  }
  if (valid_indices_.size() < static_cast<std::size_t>(nbh_.k_min)) {
    PCL_ERROR("[pcl_ls3d::%s::extract] %zu finite points, fewer than the smallest "
              "neighbourhood k_min = %d.\n",
              name, valid_indices_.size(), nbh_.k_min);
    return false;
  }
  if (valid_indices_.size() < indices_->size())
    PCL_WARN("[pcl_ls3d::%s::extract] Ignoring %zu non-finite or repeated indices.\n", name,
             indices_->size() - valid_indices_.size());

  origin_ = (*input_)[valid_indices_.front()].getVector3fMap();
  points_.resize(valid_indices_.size());
  for (std::size_t p = 0; p < valid_indices_.size(); ++p)
    points_[p] = (*input_)[valid_indices_[p]].getVector3fMap() - origin_;

  if (!search_)
    search_.reset(new pcl_ls3d::search::FlannKdTree<PointT>);
  search_->setInputCloud(
      input_, pcl::IndicesConstPtr(new pcl::Indices(valid_indices_.begin(), valid_indices_.end())));
  return true;
}

template <typename PointT, typename NormalT>
std::string
MultiRuleRegionGrowing<PointT, NormalT>::checkThresholds()
{
  // As pcl::RegionGrowing: an impossible threshold refuses the segmentation, it does not fall
  // back to a default. v_t > 0 (PCL's residual test refuses <= 0); d_t, s_t, V_t >= 0.
  char buf[160];
  if (user_residual_threshold_ &&
      !(std::isfinite(*user_residual_threshold_) && *user_residual_threshold_ > 0.0)) {
    std::snprintf(buf, sizeof(buf),
                  "Invalid residual threshold %g (must be > 0; "
                  "useAdaptiveThresholds() restores the adaptive one).",
                  *user_residual_threshold_);
    return buf;
  }
  const std::pair<const char*, const std::optional<double>*> merge_thresholds[] = {
      {"distance", &user_distance_threshold_},
      {"similarity", &user_similarity_threshold_},
      {"volume change", &user_volume_threshold_}};
  for (const auto& [what, value] : merge_thresholds)
    if (*value && !(std::isfinite(**value) && **value >= 0.0)) {
      std::snprintf(buf, sizeof(buf),
                    "Invalid %s threshold %g (must be >= 0; "
                    "useAdaptiveThresholds() restores the adaptive one).",
                    what, **value);
      return buf;
    }
  if (!(merge_.alpha > 0.0 && merge_.alpha < 1.0))
    return "The snooping significance must be in (0, 1).";
  // segment_merging.h: a negative threshold there is its adaptive rule.
  merge_.distance_threshold = user_distance_threshold_.value_or(-1.0);
  merge_.similarity_threshold = user_similarity_threshold_.value_or(-1.0);
  merge_.volume_threshold = user_volume_threshold_.value_or(-1.0);
  return "";
}

template <typename PointT, typename NormalT>
bool
MultiRuleRegionGrowing<PointT, NormalT>::computeFeatures()
{
  const int n = static_cast<int>(valid_indices_.size());
  const int gk = grow_.graph_k;
  const int k_query = std::min(n, std::max(nbh_.k_max, gk + 1));
  features_.assign(n, PointFeatures{});
  graph_.assign(static_cast<std::size_t>(n) * gk, -1);
  std::vector<double> scale(n, 0.0);  // distance to the k_min-th neighbour

#ifdef _OPENMP
#pragma omp parallel num_threads(threads_ > 0 ? threads_ : omp_get_max_threads())
#endif
  {
    pcl::Indices nn;
    std::vector<float> d2;
    std::vector<std::pair<float, int>> sorted;
    std::vector<Eigen::Vector3f> xyz;
#pragma omp for schedule(dynamic, 256)
    for (int p = 0; p < n; ++p) {
      const PointT& q = (*input_)[valid_indices_[p]];
      if (search_->nearestKSearch(q, k_query, nn, d2) <= 0)
        continue;  // stays Invalid: never labelled
      sorted.clear();
      for (std::size_t t = 0; t < nn.size(); ++t) {
        const int pos =
            (nn[t] >= 0 && static_cast<std::size_t>(nn[t]) < position_of_.size()) ? position_of_[nn[t]] : -1;
        if (pos >= 0)
          sorted.emplace_back(d2[t], pos);
      }
      if (sorted.empty())
        continue;
      if (!std::is_sorted(sorted.begin(), sorted.end()))
        std::sort(sorted.begin(), sorted.end());
      xyz.clear();
      xyz.push_back(points_[p]);  // the point itself first, whatever the duplicate order
      int g = 0;
      for (const auto& [dist2, pos] : sorted) {
        if (pos == p)
          continue;
        xyz.push_back(points_[pos]);
        if (g < gk)
          graph_[static_cast<std::size_t>(p) * gk + g++] = pos;
      }
      features_[p] = segmentation::computePointFeatures(xyz, nbh_);
      const std::size_t ks = std::min<std::size_t>(nbh_.k_min, sorted.size()) - 1;
      scale[p] = std::sqrt(static_cast<double>(sorted[ks].first));
    }
  }
  spacing_ = stats::median(scale);
  if (!(spacing_ > 0.0)) {
    PCL_ERROR("[pcl_ls3d::%s::extract] All neighbourhoods have zero extent (duplicate points "
              "only); nothing to segment.\n",
              getClassName().c_str());
    return false;
  }
  return true;
}

template <typename PointT, typename NormalT>
void
MultiRuleRegionGrowing<PointT, NormalT>::growSegments()
{
  const std::size_t n = points_.size();
  grow_.growth_radius = user_growth_radius_ > 0.0 ? user_growth_radius_ : 2.0 * spacing_;
  grow_.volumetric_radius = user_volumetric_radius_ > 0.0 ? user_volumetric_radius_ : 1.0 * spacing_;

  // v_t (§3.1): median plane-fit residual of the linear set unless given.
  grow_.residual_threshold =
      user_residual_threshold_ ? *user_residual_threshold_ : segmentation::seedResidualThreshold(features_);

  std::vector<Eigen::Vector3f> normals(n);
  for (std::size_t p = 0; p < n; ++p) {
    normals[p] = features_[p].normal;
    if (normals_) {
      const NormalT& u = (*normals_)[valid_indices_[p]];
      const Eigen::Vector3f v(u.normal_x, u.normal_y, u.normal_z);
      if (v.allFinite() && v.norm() > 0.f)
        normals[p] = v.normalized();
    }
  }
  segment_of_ = segmentation::growRegions(points_, features_, normals, graph_, grow_);
  initial_segments_ =
      segment_of_.empty()
          ? 0
          : static_cast<std::size_t>(*std::max_element(segment_of_.begin(), segment_of_.end()) + 1);
}

template <typename PointT, typename NormalT>
void
MultiRuleRegionGrowing<PointT, NormalT>::mergeSegments()
{
  std::vector<float> residuals(features_.size());
  for (std::size_t p = 0; p < features_.size(); ++p)
    residuals[p] = features_[p].residual;
  merge_.threads = threads_;
  merge_report_ =
      segmentation::mergeSegments(points_, segment_of_, residuals, merge_, spacing_ * spacing_ * spacing_);
}

template <typename PointT, typename NormalT>
void
MultiRuleRegionGrowing<PointT, NormalT>::assembleObjects()
{
  // Grid cells of two spacings hold a few points each at any density.
  segmentation::GroundFilterSettings g = ground_filter_;
  g.cell = 2.0 * spacing_;
  const std::vector<char> ground = segmentation::groundPoints(points_, g);
  std::vector<float> residuals(features_.size());
  for (std::size_t p = 0; p < features_.size(); ++p)
    residuals[p] = features_[p].residual;
  segmentation::AssemblySettings a = assembly_;
  a.max_link_length = grow_.growth_radius;  // touching = as close as growth may step
  // Crowns touch crowns through links up to halfway between the volumetric step and the
  // growth radius (1.5 spacings by default; tuned on 77050_627755, 77055_627755 and the
  // generated seeds 1-3, docs/BENCHMARKS.md).
  a.rough_link_length = 0.5 * (grow_.volumetric_radius + grow_.growth_radius);
  assembly_report_ =
      segmentation::assembleObjects(points_, graph_, grow_.graph_k, residuals, ground, a, segment_of_);
  if (min_fragment_size_ > 1) {
    // Only touching fragments join (links up to the growth radius), and rough ones never into
    // the ground, so vegetation the assembly left alone (a bush of a few points on a lawn)
    // stays its own object.
    absorbed_fragments_ += segmentation::absorbFragments(
        graph_, grow_.graph_k, segment_of_, min_fragment_size_,
        segmentation::absorptionContact(points_, assembly_report_.point_kind, a.max_link_length));
  }
  object_class_ = segmentation::classifyObjects(points_, segment_of_, assembly_report_.point_kind, ground,
                                                classes_, multipleReturnFlags());
  assignPointsByPosition(ground, a);
}

template <typename PointT, typename NormalT>
std::vector<char>
MultiRuleRegionGrowing<PointT, NormalT>::multipleReturnFlags() const
{
  // Data without returns store 1 (or 0) everywhere: no point of them is known to be single.
  // Judged on the whole input, not only on the indices segmented (its size was checked when
  // the run began; empty: unknown).
  if (!segmentation::recordsReturns(returns_))
    return {};
  std::vector<char> flags(valid_indices_.size());
  for (std::size_t p = 0; p < valid_indices_.size(); ++p)
    flags[p] = returns_[static_cast<std::size_t>(valid_indices_[p])] > 1;
  return flags;
}

template <typename PointT, typename NormalT>
void
MultiRuleRegionGrowing<PointT, NormalT>::assignPointsByPosition(const std::vector<char>& ground,
                                                                const segmentation::AssemblySettings& a)
{
  // The terrain first: the ground under an eave inside a crown object is ground, not wall.
  // Within terrain_return_multiple ground residuals of the plane the assembly measures raised
  // points against, in the same window.
  if (a.terrain_return_multiple > 0.0)
    assembly_report_.points_back_to_ground =
        segmentation::returnTerrainPoints(points_, ground, graph_, grow_.graph_k, object_class_,
                                          a.terrain_return_multiple * assembly_report_.ground_residual,
                                          segmentation::terrainWindowHalfWidth(a), segment_of_);
  // Cells of one spacing hold about three roof points; "under" is a spacing below the lowest.
  if (a.claim_under_roofs)
    assembly_report_.points_under_roofs = segmentation::claimPointsUnderRoofs(
        points_, assembly_report_.point_kind, object_class_, spacing_, spacing_, segment_of_);
}

template <typename PointT, typename NormalT>
std::vector<segmentation::ObjectClass>
MultiRuleRegionGrowing<PointT, NormalT>::clusterClasses(const std::vector<pcl::PointIndices>& clusters) const
{
  std::vector<segmentation::ObjectClass> out(clusters.size(), segmentation::ObjectClass::Unclassified);
  std::map<int, std::size_t> votes;  // object -> points of the cluster in it
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    votes.clear();
    for (const auto i : clusters[c].indices)
      if (const int object = segment_of_[static_cast<std::size_t>(position_of_[i])]; object >= 0)
        ++votes[object];
    const auto best = std::max_element(votes.begin(), votes.end(),
                                       [](const auto& a, const auto& b) { return a.second < b.second; });
    if (best != votes.end())
      out[c] = segmentation::classOf(best->first, object_class_);
  }
  return out;
}

template <typename PointT, typename NormalT>
void
MultiRuleRegionGrowing<PointT, NormalT>::assembleRegions(const std::vector<int>& labels,
                                                         std::vector<pcl::PointIndices>& clusters,
                                                         std::vector<int>& cluster_of) const
{
  const int n_labels = labels.empty() ? 0 : *std::max_element(labels.begin(), labels.end()) + 1;
  std::vector<pcl::PointIndices> all(static_cast<std::size_t>(std::max(0, n_labels)));
  for (std::size_t p = 0; p < labels.size(); ++p)
    if (labels[p] >= 0)
      all[labels[p]].indices.push_back(valid_indices_[p]);
  clusters.clear();
  cluster_of.assign(labels.size(), -1);
  for (auto& c : all) {
    // Empty: an object the point-level rules of the object level emptied.
    if (c.indices.empty() || c.indices.size() < min_cluster_size_ || c.indices.size() > max_cluster_size_)
      continue;
    for (const auto i : c.indices)
      cluster_of[position_of_[i]] = static_cast<int>(clusters.size());
    clusters.push_back(std::move(c));
  }
}

template <typename PointT, typename NormalT>
void
MultiRuleRegionGrowing<PointT, NormalT>::getSegmentFromPoint(pcl::index_t index, pcl::PointIndices& cluster)
{
  cluster.indices.clear();
  if (plane_clusters_.empty() && object_clusters_.empty()) {  // not segmented yet: as PCL, do it
    std::vector<pcl::PointIndices> clusters;
    extract(clusters);
  }
  if (index < 0 || static_cast<std::size_t>(index) >= position_of_.size())
    return;
  const int pos = position_of_[index];
  const auto& of = level_ == Level::Planes ? plane_cluster_of_ : object_cluster_of_;
  if (pos < 0 || static_cast<std::size_t>(pos) >= of.size() || of[pos] < 0)
    return;
  cluster = getClusters(level_)[of[pos]];
}

template <typename PointT, typename NormalT>
pcl::PointCloud<pcl::PointXYZRGB>::Ptr
MultiRuleRegionGrowing<PointT, NormalT>::getColoredCloud() const
{
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr out;
  const auto& clusters = getClusters(level_);
  if (!input_ || clusters.empty())
    return out;
  out.reset(new pcl::PointCloud<pcl::PointXYZRGB>);
  out->resize(input_->size());
  for (std::size_t i = 0; i < input_->size(); ++i) {
    (*out)[i].getVector3fMap() = (*input_)[i].getVector3fMap();
    (*out)[i].r = (*out)[i].g = (*out)[i].b = 255;
  }
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> colour(0, 255);
  for (const auto& c : clusters) {
    const auto r = static_cast<std::uint8_t>(colour(rng));
    const auto g = static_cast<std::uint8_t>(colour(rng));
    const auto b = static_cast<std::uint8_t>(colour(rng));
    for (const auto i : c.indices) {
      (*out)[i].r = r;
      (*out)[i].g = g;
      (*out)[i].b = b;
    }
  }
  return out;
}

template <typename PointT, typename NormalT>
std::vector<segmentation::Dimensionality>
MultiRuleRegionGrowing<PointT, NormalT>::getDimensionality() const
{
  std::vector<Dimensionality> out(position_of_.size(), Dimensionality::Invalid);
  for (std::size_t p = 0; p < features_.size(); ++p)
    out[valid_indices_[p]] = features_[p].dimensionality;
  return out;
}

template <typename PointT, typename NormalT>
bool
MultiRuleRegionGrowing<PointT, NormalT>::getPointFeatures(pcl::index_t index, PointFeatures& features) const
{
  if (index < 0 || static_cast<std::size_t>(index) >= position_of_.size())
    return false;
  const int pos = position_of_[index];
  if (pos < 0 || static_cast<std::size_t>(pos) >= features_.size())
    return false;
  features = features_[pos];
  return features.dimensionality != Dimensionality::Invalid;
}

template <typename PointT, typename NormalT>
std::vector<int>
MultiRuleRegionGrowing<PointT, NormalT>::getPointLabels() const
{
  std::vector<int> out(position_of_.size(), -1);
  const auto& of = level_ == Level::Planes ? plane_cluster_of_ : object_cluster_of_;
  for (std::size_t p = 0; p < of.size(); ++p)
    out[valid_indices_[p]] = of[p];
  return out;
}

}  // namespace pcl_ls3d

#define PCL_LS3D_INSTANTIATE_MultiRuleRegionGrowing(T)                                                       \
  template class PCL_EXPORTS pcl_ls3d::MultiRuleRegionGrowing<T, pcl::Normal>;
