#pragma once

#include <pcl_ls3d/adjustment/surface_matching_core.h>
#include <pcl_ls3d/estimators/tukey_estimator.h>
#include <pcl_ls3d/sample_consensus/sac_model_surface_matching.h>
#include <pcl_ls3d/search/flann_kd_tree.h>

#include <pcl/common/transforms.h>
#include <pcl/console/print.h>

#include <cmath>
#include <limits>

namespace pcl_ls3d {

template <typename PointT>
SampleConsensusModelSurfaceMatching<PointT>::SampleConsensusModelSurfaceMatching(
    const PointCloudConstPtr& epoch, const PointCloudConstPtr& reference, bool random)
    : Base(epoch, random)
{
  setUp(reference);
}

template <typename PointT>
SampleConsensusModelSurfaceMatching<PointT>::SampleConsensusModelSurfaceMatching(
    const PointCloudConstPtr& epoch, const pcl::Indices& indices, const PointCloudConstPtr& reference,
    bool random)
    : Base(epoch, indices, random)
{
  setUp(reference);
}

template <typename PointT>
void
SampleConsensusModelSurfaceMatching<PointT>::setUp(const PointCloudConstPtr& reference)
{
  model_name_ = "SampleConsensusModelSurfaceMatching";
  sample_size_ = 7;
  model_size_ = 7;
  rule_ = makeConjugateRule(ConjugateRuleType::LZD);
  settings_ = AdjustmentSettings::rigid6();
  settings_.automatic_reach = false;  // every epoch point keeps its residual (deformation)
  lin_ = std::make_shared<LinearizedMatching>();
  reference_ = reference;
  requested_ = indices_ ? *indices_ : pcl::Indices();
  points_.clear();
  if (input_) {
    points_.reserve(input_->size());
    for (const PointT& p : *input_)
      points_.emplace_back(p.x, p.y, p.z);  // non-finite points never overlap: no observation
  }
  std::size_t finite = 0;
  if (reference_)
    for (const PointT& p : *reference_)
      finite += std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  if (finite < 3) {
    PCL_ERROR("[pcl_ls3d::%s] the reference has fewer than 3 finite points\n", model_name_.c_str());
    return;
  }
  tree_.reset(new pcl_ls3d::search::FlannKdTree<PointT>);
  tree_->setInputCloud(reference_);
  surface_ = std::make_shared<PclTargetSurface<PointT>>(reference_, tree_);
  linearize(Eigen::Matrix4d::Identity());
}

template <typename PointT>
bool
SampleConsensusModelSurfaceMatching<PointT>::setMatching(const ConjugateRule::Ptr& rule,
                                                         const AdjustmentSettings& settings)
{
  std::string why;
  if (!rule || !settings.isValid(&why)) {
    PCL_ERROR("[pcl_ls3d::%s::setMatching] %s\n", model_name_.c_str(), rule ? why.c_str() : "null rule");
    return false;
  }
  rule_ = rule;
  settings_ = settings;
  settings_.automatic_reach = false;  // every epoch point keeps its residual (deformation)
  return linearize(start_);
}

template <typename PointT>
bool
SampleConsensusModelSurfaceMatching<PointT>::setSampleSize(unsigned int p)
{
  const int needed = lin_ && linearized_ ? lin_->freeParameters() : 6;
  if (static_cast<int>(p) < needed || p > 64) {
    PCL_ERROR("[pcl_ls3d::%s::setSampleSize] %u points cannot determine %d parameters (or more than 64)\n",
              model_name_.c_str(), p, needed);
    return false;
  }
  sample_size_ = p;
  return true;
}

template <typename PointT>
bool
SampleConsensusModelSurfaceMatching<PointT>::linearize(const Eigen::Matrix4d& start)
{
  linearized_ = false;
  start_ = start;
  if (!surface_)
    return false;
  std::string why;
  if (!rule_->prepare(*surface_, &why) || !lin_->reset(points_, *surface_, *rule_, settings_, start, &why)) {
    PCL_ERROR("[pcl_ls3d::%s::linearize] %s\n", model_name_.c_str(), why.c_str());
    return false;
  }
  pcl::Indices observed;
  observed.reserve(requested_.size());
  for (const pcl::index_t i : requested_)
    if (lin_->observationOf(i) >= 0)
      observed.push_back(i);
  indices_.reset(new pcl::Indices(std::move(observed)));
  shuffled_indices_ = *indices_;
  linearized_ = true;
  return true;
}

template <typename PointT>
Vector7d
SampleConsensusModelSurfaceMatching<PointT>::parameters(const Eigen::VectorXf& c) const
{
  return c.head<7>().template cast<double>();
}

template <typename PointT>
Eigen::VectorXf
SampleConsensusModelSurfaceMatching<PointT>::toCoefficients(const Eigen::Matrix4d& T) const
{
  return lin_->parametersOf(T).template cast<float>();
}

template <typename PointT>
Eigen::Matrix4d
SampleConsensusModelSurfaceMatching<PointT>::toMatrix(const Eigen::VectorXf& c) const
{
  return lin_->matrixOf(parameters(c));
}

template <typename PointT>
bool
SampleConsensusModelSurfaceMatching<PointT>::isModelValid(const Eigen::VectorXf& c) const
{
  return c.size() == 7 && c.allFinite() && c[SCALE] > 0.f;
}

template <typename PointT>
bool
SampleConsensusModelSurfaceMatching<PointT>::isSampleGood(const pcl::Indices& samples) const
{
  if (!linearized_)
    return false;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    if (lin_->observationOf(samples[k]) < 0)
      return false;
    for (std::size_t j = 0; j < k; ++j)
      if (samples[j] == samples[k])
        return false;
  }
  return true;
}

template <typename PointT>
bool
SampleConsensusModelSurfaceMatching<PointT>::computeModelCoefficients(const pcl::Indices& samples,
                                                                      Eigen::VectorXf& c) const
{
  if (!linearized_ || samples.size() != sample_size_)
    return false;
  std::vector<int> obs;
  for (const pcl::index_t i : samples) {
    const int first = lin_->observationOf(i);
    if (first < 0)
      return false;
    for (int j = 0; j < lin_->countOf(i); ++j)
      obs.push_back(first + j);
  }
  Vector7d X;
  if (!lin_->fit(obs.data(), obs.size(), X))
    return false;
  c = X.cast<float>();
  return isModelValid(c);
}

template <typename PointT>
double
SampleConsensusModelSurfaceMatching<PointT>::distanceOf(pcl::index_t index, const Vector7d& X) const
{
  const int first = lin_->observationOf(index);
  if (first < 0)
    return std::numeric_limits<double>::infinity();
  double d = 0.0;  // several observations of one point (ICP rule): the largest
  for (int j = 0; j < lin_->countOf(index); ++j)
    d = std::max(d, std::abs(lin_->residual(static_cast<std::size_t>(first + j), X)));
  return d;
}

template <typename PointT>
void
SampleConsensusModelSurfaceMatching<PointT>::getResidualsToModel(const Eigen::VectorXf& c,
                                                                 std::vector<double>& residuals) const
{
  residuals.assign(indices_->size(), std::numeric_limits<double>::quiet_NaN());
  if (!linearized_ || !isModelValid(c))
    return;
  const Vector7d X = parameters(c);
  for (std::size_t k = 0; k < indices_->size(); ++k) {
    const int first = lin_->observationOf((*indices_)[k]);
    if (first >= 0)
      residuals[k] = lin_->residual(static_cast<std::size_t>(first), X);
  }
}

template <typename PointT>
void
SampleConsensusModelSurfaceMatching<PointT>::getDistancesToModel(const Eigen::VectorXf& c,
                                                                 std::vector<double>& distances) const
{
  distances.clear();
  if (!linearized_ || !isModelValid(c))
    return;  // an empty vector tells PCL's estimators the model is unusable
  const Vector7d X = parameters(c);
  distances.resize(indices_->size());
  for (std::size_t k = 0; k < indices_->size(); ++k)
    distances[k] = distanceOf((*indices_)[k], X);
}

template <typename PointT>
void
SampleConsensusModelSurfaceMatching<PointT>::selectWithinDistance(const Eigen::VectorXf& c,
                                                                  const double threshold,
                                                                  pcl::Indices& inliers)
{
  inliers.clear();
  error_sqr_dists_.clear();
  if (!linearized_ || !isModelValid(c))
    return;
  const Vector7d X = parameters(c);
  for (const pcl::index_t i : *indices_) {
    const double d = distanceOf(i, X);
    if (d <= threshold) {
      inliers.push_back(i);
      error_sqr_dists_.push_back(d * d);
    }
  }
}

template <typename PointT>
std::size_t
SampleConsensusModelSurfaceMatching<PointT>::countWithinDistance(const Eigen::VectorXf& c,
                                                                 const double threshold) const
{
  if (!linearized_ || !isModelValid(c))
    return 0;
  const Vector7d X = parameters(c);
  std::size_t n = 0;
  for (const pcl::index_t i : *indices_)
    n += distanceOf(i, X) <= threshold;
  return n;
}

template <typename PointT>
bool
SampleConsensusModelSurfaceMatching<PointT>::doSamplesVerifyModel(const std::set<pcl::index_t>& indices,
                                                                  const Eigen::VectorXf& c,
                                                                  const double threshold) const
{
  if (!linearized_ || !isModelValid(c))
    return false;
  const Vector7d X = parameters(c);
  for (const pcl::index_t i : indices)
    if (!(distanceOf(i, X) <= threshold))
      return false;
  return true;
}

template <typename PointT>
void
SampleConsensusModelSurfaceMatching<PointT>::optimizeModelCoefficients(const pcl::Indices& inliers,
                                                                       const Eigen::VectorXf& c,
                                                                       Eigen::VectorXf& optimized) const
{
  optimized = c;
  if (!linearized_ || !isModelValid(c) || inliers.size() < sample_size_)
    return;
  std::vector<Eigen::Vector3d> points;
  std::vector<int> index_of;
  for (const pcl::index_t i : inliers) {
    const Eigen::Vector3d& p = points_[static_cast<std::size_t>(i)];
    if (p.allFinite()) {
      points.push_back(p);
      index_of.push_back(static_cast<int>(i));
    }
  }
  SurfaceMatchingCore core;
  const TukeyEstimator tukey;  // c = 4.685, 1.4826 MAD (Li eqs. 6–7)
  AdjustmentSettings s = settings_;
  s.store_observations = false;
  const AdjustmentReport r = core.run(points, index_of, *surface_, *rule_, tukey, s, toMatrix(c));
  if (r.isSolutionUsable())
    optimized = toCoefficients(r.transformation);
  else
    PCL_WARN("[pcl_ls3d::%s::optimizeModelCoefficients] IRLS failed (%s): coefficients unchanged\n",
             model_name_.c_str(), r.message.c_str());
}

template <typename PointT>
void
SampleConsensusModelSurfaceMatching<PointT>::projectPoints(const pcl::Indices& inliers,
                                                           const Eigen::VectorXf& c, PointCloud& projected,
                                                           bool copy_data_fields) const
{
  if (copy_data_fields)
    projected = *input_;
  else {
    projected.clear();
    projected.resize(inliers.size());
  }
  if (!linearized_ || !isModelValid(c))
    return;
  const Eigen::Matrix4d T = toMatrix(c);
  const Vector7d X = parameters(c);
  auto move = [&](pcl::index_t i, PointT& out) {
    const Eigen::Vector3d x = (T * points_[static_cast<std::size_t>(i)].homogeneous()).head<3>();
    Eigen::Vector3d y = x;
    const int first = lin_->observationOf(i);
    if (first >= 0) {
      const Eigen::Vector3d& u = lin_->observations()[static_cast<std::size_t>(first)].direction;
      y = x - lin_->residual(static_cast<std::size_t>(first), X) * u / u.squaredNorm();
    }
    out.x = static_cast<float>(y.x());
    out.y = static_cast<float>(y.y());
    out.z = static_cast<float>(y.z());
  };
  if (copy_data_fields) {
    pcl::transformPointCloud(*input_, projected, T.cast<float>());
    for (const pcl::index_t i : inliers)
      move(i, projected[static_cast<std::size_t>(i)]);
  } else
    for (std::size_t k = 0; k < inliers.size(); ++k) {
      projected[k] = (*input_)[static_cast<std::size_t>(inliers[k])];
      move(inliers[k], projected[k]);
    }
}

}  // namespace pcl_ls3d

#define PCL_LS3D_INSTANTIATE_SampleConsensusModelSurfaceMatching(T)                                          \
  template class PCL_EXPORTS pcl_ls3d::SampleConsensusModelSurfaceMatching<T>;
