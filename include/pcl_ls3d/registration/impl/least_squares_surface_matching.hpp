#pragma once

#include <pcl_ls3d/registration/least_squares_surface_matching.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/registration/point_to_point_rule.h>
#include <pcl_ls3d/search/flann_kd_tree.h>

#include <pcl/common/io.h>
#include <pcl/common/transforms.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace pcl_ls3d {

template <typename PointSource, typename PointTarget, typename Scalar>
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::LeastSquaresSurfaceMatching()
    : rule_(makeConjugateRule(ConjugateRuleType::LND)), estimator_(std::make_shared<ZuoEstimator>(6.0))
{
  reg_name_ = "LeastSquaresSurfaceMatching";
  max_iterations_ = settings_.max_iterations;
  tree_.reset(new pcl_ls3d::search::FlannKdTree<PointTarget>);  // same tree as PCL's, cheaper queries
  default_correspondence_estimation_ = correspondence_estimation_;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::setConjugateRule(ConjugateRuleType type)
{
  rule_ = makeConjugateRule(type);
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::setConjugateRule(
    const ConjugateRule::Ptr& rule)
{
  if (!rule) {
    PCL_ERROR("[pcl_ls3d::%s::setConjugateRule] null rule ignored\n", getClassName().c_str());
    return;
  }
  rule_ = rule;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::setRobustEstimator(
    const RobustEstimator::Ptr& estimator)
{
  if (!estimator) {
    PCL_ERROR("[pcl_ls3d::%s::setRobustEstimator] null estimator ignored\n", getClassName().c_str());
    return;
  }
  estimator_ = estimator;
}

template <typename PointSource, typename PointTarget, typename Scalar>
bool
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::setAdjustmentSettings(
    const AdjustmentSettings& settings)
{
  std::string why;
  if (!settings.isValid(&why)) {
    PCL_ERROR("[pcl_ls3d::%s::setAdjustmentSettings] %s\n", getClassName().c_str(), why.c_str());
    return false;
  }
  settings_ = settings;
  max_iterations_ = settings.max_iterations;
  corr_dist_threshold_ = settings.max_correspondence_distance;
  // The settings' own epsilons rule from now on: PCL's (which override them) are unset.
  transformation_epsilon_ = 0.0;
  transformation_rotation_epsilon_ = 0.0;
  return true;
}

template <typename PointSource, typename PointTarget, typename Scalar>
AdjustmentSettings
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::getAdjustmentSettings() const
{
  AdjustmentSettings s = settings_;
  s.max_iterations = max_iterations_;
  s.max_correspondence_distance = corr_dist_threshold_;
  // As pcl::DefaultConvergenceCriteria set up by ICP: the transformation epsilon is a squared
  // translation, and without a rotation epsilon 1 − epsilon is the cosine of the largest
  // rotation change still "converged"; a rotation epsilon is that cosine itself.
  if (transformation_epsilon_ > 0.0) {
    s.translation_epsilon = std::sqrt(transformation_epsilon_);
    // cos θ = 1 − ε, written so that a tiny ε keeps its precision: θ = 2 asin(√(ε / 2)).
    s.angle_epsilon = 2.0 * std::asin(std::sqrt(std::min(1.0, 0.5 * transformation_epsilon_)));
  }
  if (transformation_rotation_epsilon_ > 0.0 && transformation_rotation_epsilon_ < 1.0)
    s.angle_epsilon = std::acos(transformation_rotation_epsilon_);
  return s;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::collectSourcePoints(
    double thinning, std::vector<Eigen::Vector3d>& points, std::vector<int>& index_of) const
{
  // Finite source points over indices_, as PCL does; then regular thinning.
  points.reserve(indices_->size());
  index_of.reserve(indices_->size());
  for (const auto idx : *indices_) {
    const PointSource& p = (*input_)[static_cast<std::size_t>(idx)];
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
      points.emplace_back(p.x, p.y, p.z);
      index_of.push_back(static_cast<int>(idx));
    }
  }
  if (!(thinning > 0.0))
    return;
  const std::vector<int> keep = thinByVoxel(points, thinning);
  std::vector<Eigen::Vector3d> thinned(keep.size());
  std::vector<int> thinned_index(keep.size());
  for (std::size_t i = 0; i < keep.size(); ++i) {
    thinned[i] = points[static_cast<std::size_t>(keep[i])];
    thinned_index[i] = index_of[static_cast<std::size_t>(keep[i])];
  }
  points.swap(thinned);
  index_of.swap(thinned_index);
}

template <typename PointSource, typename PointTarget, typename Scalar>
std::string
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::checkInputs(
    const std::vector<Eigen::Vector3d>& points, const TargetSurface& surface, ConjugateRule& rule) const
{
  if (points.empty())
    return "the source cloud has no finite point";
  std::size_t finite_target = 0;
  for (const auto& p : *target_)
    finite_target += std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  if (finite_target < 3)
    return "the target cloud has fewer than 3 finite points";
  std::string why;
  if (!rule.prepare(surface, &why))
    return "rule " + rule.name() + " could not prepare: " + why;
  return "";
}

template <typename PointSource, typename PointTarget, typename Scalar>
bool
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::overlapsTarget(
    const std::vector<Eigen::Vector3d>& points, const Eigen::Matrix4d& guess) const
{
  Eigen::AlignedBox3d box, moved;
  for (const auto& p : *target_)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
      box.extend(Eigen::Vector3d(p.x, p.y, p.z));
  const double margin = 0.1 * box.diagonal().norm();  // the engine's margin (setUpPair)
  Eigen::AlignedBox3d grown = box;
  grown.min().array() -= margin;
  grown.max().array() += margin;
  for (const auto& p : points) {
    const Eigen::Vector3d x = (guess * p.homogeneous()).template head<3>();
    if (grown.contains(x))
      return true;
    moved.extend(x);
  }
  // Beside the target by less than the clouds' own size (the bunny moved by 0.2 m): worth a
  // start at the centroids. Farther (a tile 10 km away) stays a refusal (NO_OVERLAP).
  const double gap = (moved.center() - box.center()).norm();
  return gap > 2.0 * std::max(box.diagonal().norm(), moved.diagonal().norm());
}

template <typename PointSource, typename PointTarget, typename Scalar>
Eigen::Matrix4d
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::centroidStart(
    const std::vector<Eigen::Vector3d>& points, const Eigen::Matrix4d& guess) const
{
  Eigen::Vector3d cs = Eigen::Vector3d::Zero(), ct = Eigen::Vector3d::Zero();
  for (const auto& p : points)
    cs += (guess * p.homogeneous()).template head<3>();
  cs /= static_cast<double>(points.size());
  std::size_t n = 0;
  for (const auto& p : *target_)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
      ct += Eigen::Vector3d(p.x, p.y, p.z);
      ++n;
    }
  ct /= static_cast<double>(std::max<std::size_t>(n, 1));
  Eigen::Matrix4d start = guess;
  start.template topRightCorner<3, 1>() += ct - cs;
  return start;
}

template <typename PointSource, typename PointTarget, typename Scalar>
ConjugateRule::Ptr
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::ruleForSize(std::size_t source_points,
                                                                           AdjustmentSettings& settings) const
{
  std::size_t finite_target = 0;
  for (const auto& p : *target_)
    finite_target += std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  const auto min_obs = static_cast<std::size_t>(std::max(0, settings.min_observations));
  // Only when both clouds are tiny: a big source on a handful of target points stays refused.
  if (finite_target >= kTinyCloud || source_points >= std::max(min_obs, kTinyCloud))
    return rule_;
  // Too few points for a local surface (LND/LZD fit 20 neighbours) or for the minimum number of
  // observations: point-to-point observations (three per source point, as ICP's), and a minimum
  // that a tiny cloud can meet (ICP needs 3 correspondences; here 6 parameters + 1 redundancy).
  settings.min_observations = static_cast<int>(std::min<std::size_t>(min_obs, 7));
  PCL_WARN("[pcl_ls3d::%s::align] tiny clouds (%zu source / %zu target points): point-to-point "
           "observations instead of rule %s, minimum %d observations\n",
           getClassName().c_str(), source_points, finite_target, rule_->name().c_str(),
           settings.min_observations);
  return std::make_shared<PointToPointRule>();
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::adoptReport()
{
  nr_iterations_ = report_.iterations;
  // An estimate that failed the quality gate stays readable (for inspection) but is not converged.
  if (report_.hasEstimate())
    final_transformation_ = report_.transformation.template cast<Scalar>();
  // As pcl::DefaultConvergenceCriteria: reaching the iteration limit counts as converged
  // unless failure_after_max_iter is set; report_.termination tells them apart.
  converged_ = report_.isSolutionUsable() &&
               (report_.termination == TerminationType::CONVERGED || !failure_after_max_iter_);
  if (report_.isSolutionUsable()) {
    if (!report_.message.empty())
      PCL_WARN("[pcl_ls3d::%s::computeTransformation] %s\n", getClassName().c_str(), report_.message.c_str());
  } else {
    PCL_ERROR("[pcl_ls3d::%s::computeTransformation] %s: %s\n", getClassName().c_str(),
              terminationTypeToString(report_.termination), report_.message.c_str());
  }
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::adoptIncrements()
{
  // ICP leaves both at the identity when nothing was estimated; final_transformation_ then
  // stays the guess too.
  if (nr_iterations_ == 0 || !report_.hasEstimate()) {
    transformation_ = previous_transformation_ = Matrix4::Identity();
    return;
  }
  transformation_ = (pose_last_ * pose_before_.inverse()).template cast<Scalar>();
  previous_transformation_ = (pose_before_ * pose_before_that_.inverse()).template cast<Scalar>();
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::warnIgnoredStrategies()
{
  if (transformation_estimation_ && !warned_estimation_) {
    PCL_WARN("[pcl_ls3d::%s::align] setTransformationEstimation() is ignored: LS3D estimates the "
             "transformation by its own Gauss-Markov adjustment (choose the conjugate rule "
             "instead, e.g. LND for point-to-plane)\n",
             getClassName().c_str());
    warned_estimation_ = true;
  }
  if (correspondence_estimation_ != default_correspondence_estimation_ && !warned_correspondence_) {
    PCL_WARN("[pcl_ls3d::%s::align] setCorrespondenceEstimation() is ignored: the conjugate "
             "rule (setConjugateRule) finds the correspondences\n",
             getClassName().c_str());
    warned_correspondence_ = true;
  }
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::transformInput(const Eigen::Matrix4d& pose,
                                                                              PointCloudSource& out) const
{
  const Matrix4 t = pose.template cast<Scalar>();
  if constexpr (pcl::traits::has_normal_v<PointSource>)
    pcl::transformPointCloudWithNormals(*input_, out, t);
  else
    pcl::transformPointCloud(*input_, out, t);
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::observationCorrespondences(
    const Eigen::Matrix4d& pose, const ObservationSet& obs, const std::vector<int>& index_of,
    const TargetSurface& surface, pcl::Correspondences& corr, std::vector<std::size_t>& first_obs) const
{
  corr.clear();
  first_obs.clear();
  std::vector<int> nn(1);
  std::vector<float> d2(1);
  for (std::size_t j = 0; j < obs.size(); ++j) {
    const Observation& o = obs[j];
    if (j > 0 && obs[j - 1].point == o.point)
      continue;  // one correspondence per source point (ICP's three axes share it)
    if (surface.nearestKSearch(o.foot, 1, nn, d2) < 1)
      continue;
    const int source_index = index_of[static_cast<std::size_t>(o.point)];
    const PointSource& p = (*input_)[static_cast<std::size_t>(source_index)];
    const Eigen::Vector3d x = (pose * Eigen::Vector4d(p.x, p.y, p.z, 1.0)).template head<3>();
    const float dist2 = static_cast<float>((x - surface.point(nn[0])).squaredNorm());
    corr.emplace_back(source_index, nn[0], dist2);
    first_obs.push_back(j);
  }
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::rejectObservations(
    const Eigen::Matrix4d& pose, const ObservationSet& obs, const std::vector<int>& index_of,
    const TargetSurface& surface, std::vector<char>& keep)
{
  auto all = std::make_shared<pcl::Correspondences>();
  std::vector<std::size_t> first_obs;
  observationCorrespondences(pose, obs, index_of, surface, *all, first_obs);
  // As IterativeClosestPoint::computeTransformation: the transformed input as a blob for the
  // rejectors that need source points or normals, then each rejector on the previous survivors.
  pcl::PCLPointCloud2::Ptr source_blob;
  for (const auto& rej : correspondence_rejectors_)
    if (rej->requiresSourcePoints() || rej->requiresSourceNormals()) {
      PointCloudSource moved;
      transformInput(pose, moved);
      source_blob.reset(new pcl::PCLPointCloud2);
      pcl::toPCLPointCloud2(moved, *source_blob);
      break;
    }
  auto current = std::make_shared<pcl::Correspondences>(*all);
  pcl::Correspondences survivors;
  for (const auto& rej : correspondence_rejectors_) {
    if (rej->requiresSourcePoints())
      rej->setSourcePoints(source_blob);
    if (rej->requiresSourceNormals() && pcl::traits::has_normal_v<PointSource>)
      rej->setSourceNormals(source_blob);
    rej->setInputCorrespondences(current);
    rej->getCorrespondences(survivors);
    *current = survivors;
  }
  // Observations of source points whose correspondence survived are kept.
  std::vector<char> point_kept(index_of.size(), 0);
  std::vector<int> position(input_->size(), -1);
  for (std::size_t k = 0; k < all->size(); ++k)
    position[static_cast<std::size_t>((*all)[k].index_query)] = obs[first_obs[k]].point;
  for (const auto& c : *current)
    if (c.index_query >= 0 && static_cast<std::size_t>(c.index_query) < position.size() &&
        position[static_cast<std::size_t>(c.index_query)] >= 0)
      point_kept[static_cast<std::size_t>(position[static_cast<std::size_t>(c.index_query)])] = 1;
  for (std::size_t j = 0; j < obs.size(); ++j)
    keep[j] = point_kept[static_cast<std::size_t>(obs[j].point)];
}

template <typename PointSource, typename PointTarget, typename Scalar>
IterationHooks
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::pclHooks(const std::vector<int>& index_of,
                                                                        const TargetSurface& surface)
{
  IterationHooks hooks;
  if (!correspondence_rejectors_.empty()) {
    target_blob_.reset(new pcl::PCLPointCloud2);
    pcl::toPCLPointCloud2(*target_, *target_blob_);
    for (const auto& rej : correspondence_rejectors_) {
      if (rej->requiresTargetPoints())
        rej->setTargetPoints(target_blob_);
      if (rej->requiresTargetNormals() && pcl::traits::has_normal_v<PointTarget>)
        rej->setTargetNormals(target_blob_);
    }
    hooks.filter = [this, &index_of, &surface](const Eigen::Matrix4d& pose, const ObservationSet& obs,
                                               std::vector<char>& keep) {
      rejectObservations(pose, obs, index_of, surface, keep);
    };
  }
  previous_mse_ = std::numeric_limits<double>::max();
  hooks.after_iteration = [this, &index_of, &surface](const IterationRecord& rec, const Eigen::Matrix4d& pose,
                                                      const ObservationSet& obs) {
    nr_iterations_ = rec.iteration;  // as ICP: counted while iterating
    pose_before_that_ = pose_before_;
    pose_before_ = pose_last_;
    pose_last_ = pose;
    if (update_visualizer_) {
      pcl::Correspondences corr;
      std::vector<std::size_t> first_obs;
      observationCorrespondences(pose, obs, index_of, surface, corr, first_obs);
      pcl::Indices source_good, target_good;
      for (const auto& c : corr) {
        source_good.push_back(c.index_query);
        target_good.push_back(c.index_match);
      }
      PointCloudSource moved;
      transformInput(pose, moved);
      update_visualizer_(moved, source_good, *target_, target_good);
    }
    // pcl::registration::DefaultConvergenceCriteria's relative MSE test (euclidean fitness
    // epsilon), on the mean squared observation l² of this iteration.
    double mse = 0.0;
    for (const auto& o : obs)
      mse += o.distance * o.distance;
    mse = obs.empty() ? 0.0 : mse / static_cast<double>(obs.size());
    const bool similar = std::abs(mse - previous_mse_) / previous_mse_ < euclidean_fitness_epsilon_;
    previous_mse_ = mse;
    return similar;
  };
  return hooks;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::computeTransformation(PointCloudSource& output,
                                                                                     const Matrix4& guess)
{
  nr_iterations_ = 0;
  converged_ = false;
  final_transformation_ = guess;
  report_ = AdjustmentReport();
  report_.rule_name = rule_->name();
  report_.estimator_name = estimator_->name();

  AdjustmentSettings settings = getAdjustmentSettings();
  std::vector<Eigen::Vector3d> points;
  std::vector<int> index_of;
  collectSourcePoints(settings.source_thinning, points, index_of);
  const PclTargetSurface<PointTarget> surface(target_, tree_);
  const ConjugateRule::Ptr rule = ruleForSize(points.size(), settings);
  const std::string invalid = checkInputs(points, surface, *rule);
  if (!invalid.empty()) {
    report_.termination = TerminationType::INVALID_INPUT;
    report_.message = invalid;
    PCL_ERROR("[pcl_ls3d::%s::computeTransformation] %s\n", getClassName().c_str(), invalid.c_str());
  } else {
    warnIgnoredStrategies();
    core_.setHooks(pclHooks(index_of, surface));
    Eigen::Matrix4d start = guess.template cast<double>();
    if (isUnlimitedDistance(settings.max_correspondence_distance) && !overlapsTarget(points, start)) {
      // The source lies beside the target (e.g. moved beyond its own size): ICP would still pair
      // every point; LS3D starts with the centroids made to coincide instead of no observation.
      PCL_WARN("[pcl_ls3d::%s::computeTransformation] no source point over the target under the "
               "guess; starting with the centroids made to coincide\n",
               getClassName().c_str());
      start = centroidStart(points, start);
    }
    pose_last_ = pose_before_ = pose_before_that_ = start;
    report_ = core_.run(points, index_of, surface, *rule, *estimator_, settings, start);
    core_.setHooks(IterationHooks());
    adoptReport();
  }
  adoptIncrements();
  transformInput(final_transformation_.template cast<double>(), output);  // as ICP: normals too
}

}  // namespace pcl_ls3d

#define PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(S, T)                                               \
  template class PCL_EXPORTS pcl_ls3d::LeastSquaresSurfaceMatching<S, T, float>;
