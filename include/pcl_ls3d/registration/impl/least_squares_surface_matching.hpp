#pragma once

#include <pcl_ls3d/registration/least_squares_surface_matching.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>

#include <pcl/common/transforms.h>
#include <pcl/console/print.h>

#include <cmath>

namespace pcl_ls3d {

template <typename PointSource, typename PointTarget, typename Scalar>
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::LeastSquaresSurfaceMatching()
: rule_(makeConjugateRule(ConjugateRuleType::LND))
, estimator_(std::make_shared<ZuoEstimator>(6.0))
{
  reg_name_ = "LeastSquaresSurfaceMatching";
  max_iterations_ = settings_.max_iterations;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::setConjugateRule(
    ConjugateRuleType type)
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
    PCL_ERROR("[pcl_ls3d::%s::setRobustEstimator] null estimator ignored\n",
              getClassName().c_str());
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
  transformation_epsilon_ = settings.translation_epsilon * settings.translation_epsilon;
  return true;
}

template <typename PointSource, typename PointTarget, typename Scalar>
AdjustmentSettings
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::getAdjustmentSettings() const
{
  AdjustmentSettings s = settings_;
  s.max_iterations = max_iterations_;
  s.max_correspondence_distance = corr_dist_threshold_;
  if (transformation_epsilon_ > 0.0)  // PCL's epsilon is a squared translation
    s.translation_epsilon = std::sqrt(transformation_epsilon_);
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
    const std::vector<Eigen::Vector3d>& points, const TargetSurface& surface) const
{
  if (points.empty())
    return "the source cloud has no finite point";
  std::size_t finite_target = 0;
  for (const auto& p : *target_)
    finite_target += std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  if (finite_target < 3)
    return "the target cloud has fewer than 3 finite points";
  std::string why;
  if (!rule_->prepare(surface, &why))
    return "rule " + rule_->name() + " could not prepare: " + why;
  return "";
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::adoptReport()
{
  nr_iterations_ = report_.iterations;
  if (report_.isSolutionUsable()) {
    final_transformation_ = report_.transformation.template cast<Scalar>();
    // As pcl::DefaultConvergenceCriteria: reaching the iteration limit counts as converged
    // unless failure_after_max_iter is set; report_.termination tells them apart.
    converged_ = report_.termination == TerminationType::CONVERGED || !failure_after_max_iter_;
    if (!report_.message.empty())
      PCL_WARN("[pcl_ls3d::%s::computeTransformation] %s\n", getClassName().c_str(),
               report_.message.c_str());
  }
  else {
    PCL_ERROR("[pcl_ls3d::%s::computeTransformation] %s: %s\n", getClassName().c_str(),
              terminationTypeToString(report_.termination), report_.message.c_str());
  }
}

template <typename PointSource, typename PointTarget, typename Scalar>
void
LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>::computeTransformation(
    PointCloudSource& output, const Matrix4& guess)
{
  nr_iterations_ = 0;
  converged_ = false;
  final_transformation_ = guess;
  report_ = AdjustmentReport();
  report_.rule_name = rule_->name();
  report_.estimator_name = estimator_->name();

  const AdjustmentSettings settings = getAdjustmentSettings();
  std::vector<Eigen::Vector3d> points;
  std::vector<int> index_of;
  collectSourcePoints(settings.source_thinning, points, index_of);
  const PclTargetSurface<PointTarget> surface(target_, tree_);
  const std::string invalid = checkInputs(points, surface);
  if (!invalid.empty()) {
    report_.termination = TerminationType::INVALID_INPUT;
    report_.message = invalid;
    PCL_ERROR("[pcl_ls3d::%s::computeTransformation] %s\n", getClassName().c_str(), invalid.c_str());
  }
  else {
    report_ = core_.run(points, index_of, surface, *rule_, *estimator_, settings,
                        guess.template cast<double>());
    adoptReport();
  }
  transformation_ = final_transformation_;
  previous_transformation_ = final_transformation_;
  output = *input_;
  pcl::transformPointCloud(*input_, output, final_transformation_);
}

}  // namespace pcl_ls3d

#define PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(S, T)                               \
  template class PCL_EXPORTS pcl_ls3d::LeastSquaresSurfaceMatching<S, T, float>;
