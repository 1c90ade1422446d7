#pragma once
/// \file least_squares_surface_matching.h
/// \brief Least-squares 3-D surface matching (LS3D, Zuo et al. 2012) as a pcl::Registration:
///        a drop-in for pcl::IterativeClosestPoint that estimates a 7-parameter similarity with
///        pluggable conjugate-point rules (LND, LZD, ICP or your own), a-priori parameter
///        observations, robust weights, and a full precision / reliability report.

#include <pcl_ls3d/adjustment/adjustment_report.h>
#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/adjustment/surface_matching_core.h>
#include <pcl_ls3d/estimators/robust_estimator.h>
#include <pcl_ls3d/rules/conjugate_rule.h>

#include <pcl/PCLPointCloud2.h>
#include <pcl/correspondence.h>
#include <pcl/registration/registration.h>

#include <memory>
#include <string>
#include <vector>

namespace pcl_ls3d {

/// \brief LS3D registration. Usage is that of pcl::IterativeClosestPoint:
/// \code
///   pcl_ls3d::LeastSquaresSurfaceMatching<PointT, PointT> ls3d;
///   ls3d.setInputSource(source); ls3d.setInputTarget(target);
///   ls3d.align(aligned);                      // or align(aligned, guess)
///   if (ls3d.hasConverged()) T = ls3d.getFinalTransformation();
///   const auto& report = ls3d.getReport();    // σ0, σ_i, Qxx, correlation, r_i, ...
/// \endcode
/// getFinalTransformation() maps source into target coordinates (x' = m R x + t, as a 4×4).
/// Defaults: LND rule (normal distance to a local quadric of 20 target neighbours; Zuo's TIN
/// facet is LndRule::Surface::TRIANGLE), Zuo's 0/1 weight at 6σ0 (eq. 15), all 7 parameters
/// free, 30 iterations, convergence when every angle change < 1e-6 rad and |dt| < 1e-5 (and
/// |dm| < 1e-8). Clouds above 400 k source points start coarse (every k-th point) until the
/// estimate settles, then use every point; conjugate points are frozen for the last iterations.
/// Precision: σ_i come from the spatial sandwich covariance (spatial_precision.h), because
/// neighbouring observations share target points; the formal σ0 √q_ii of eq. 14 (≈ 1.5–2× too
/// small on noisy data) is kept as report.sigmas_formal. The scale column is corrected for the
/// source's own noise (errors in variables; AdjustmentSettings::correct_source_noise).
/// With a finite setMaxCorrespondenceDistance() source points with no target point within it
/// are culled by a grid look-up before any neighbour search (overlap_grid.h).
/// Base-class knobs keep their PCL meaning: setMaximumIterations(), setMaxCorrespondenceDistance(),
/// setSearchMethodTarget() (the kd-tree is reused across iterations and across align() calls
/// on the same target).
/// Also honoured as in pcl::IterativeClosestPoint (PCL 1.13.1), with every rule:
/// - setTransformationEpsilon(ε > 0): as ICP sets up DefaultConvergenceCriteria, a squared
///   translation (√ε replaces the translation epsilon) and, unless a rotation epsilon is set,
///   1 − ε is the cosine of the largest rotation change still converged (the angle epsilon
///   becomes acos(1 − ε); 1e-8 gives 1.4e-4 rad, looser than LS3D's own 1e-6). The test is on
///   the iteration's step in the reduced frame, where ICP tests the increment's translation in
///   cloud coordinates (which also holds the rotation about the cloud's origin). 0 (PCL's
///   default, with which ICP never converges by this test) keeps LS3D's own epsilons.
/// - setTransformationRotationEpsilon(): a cosine; acos of it replaces the angle epsilon.
/// - getLastIncrementalTransformation(): the last iteration's step as a 4×4 in cloud
///   coordinates (final = step × the pose before it), identity when nothing was estimated.
/// - setEuclideanFitnessEpsilon(): DefaultConvergenceCriteria's relative-MSE test, on the mean
///   squared observation l² of consecutive iterations (an epsilon > 1 stops after one, as ICP).
/// - addCorrespondenceRejector(): the rejectors run on every iteration's observations, in order,
///   with the blobs ICP gives them (target once, transformed source per iteration); each observed
///   source point is one pcl::Correspondence (index_query = its cloud index, index_match = the
///   target point nearest its conjugate point, distance = their squared distance) and the
///   observations of rejected points are dropped before weighting.
/// - registerVisualizationCallback(): called after every iteration with the transformed source,
///   the observed source indices and their target points.
/// - nr_iterations_: reset by computeTransformation() and counted per iteration; align() itself
///   does not reset it (nor converged_ when initCompute() fails), exactly as for ICP.
/// Ignored: setTransformationEstimation() (the Gauss–Markov adjustment is the estimation; choose
/// the conjugate rule, LND for point-to-plane) and setCorrespondenceEstimation() (the rule finds
/// correspondences) — each warns once; setRANSACOutlierRejectionThreshold() (ICP 1.13.1 reads
/// inlier_threshold_ nowhere either), setUseReciprocalCorrespondences(), setSearchMethodSource().
/// Tiny clouds (< 20 target and < 20 source points, e.g. PCL's five-point ICP_translated) use
/// point-to-point observations (point_to_point_rule.h) and a minimum of 7 observations.
/// With an unlimited correspondence distance, a guess under which no source point lies over the
/// target's box but whose centre is within two cloud diagonals of the target's (the source moved
/// by about its own size) is not refused as NO_OVERLAP: the
/// adjustment starts with the centroids made to coincide (PCL_WARN), where ICP would pair every
/// point anyway.
template <typename PointSource, typename PointTarget, typename Scalar = float>
class LeastSquaresSurfaceMatching : public pcl::Registration<PointSource, PointTarget, Scalar>
{
public:
  using Base = pcl::Registration<PointSource, PointTarget, Scalar>;
  using PointCloudSource = typename Base::PointCloudSource;
  using PointCloudSourcePtr = typename PointCloudSource::Ptr;
  using PointCloudSourceConstPtr = typename PointCloudSource::ConstPtr;
  using PointCloudTarget = typename Base::PointCloudTarget;
  using PointCloudTargetPtr = typename PointCloudTarget::Ptr;
  using PointCloudTargetConstPtr = typename PointCloudTarget::ConstPtr;
  using KdTree = typename Base::KdTree;
  using KdTreePtr = typename Base::KdTreePtr;
  using Matrix4 = typename Base::Matrix4;

  using Ptr = std::shared_ptr<LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>>;
  using ConstPtr = std::shared_ptr<const LeastSquaresSurfaceMatching<PointSource, PointTarget, Scalar>>;

  using Base::converged_;
  using Base::corr_dist_threshold_;
  using Base::correspondence_estimation_;
  using Base::correspondence_rejectors_;
  using Base::euclidean_fitness_epsilon_;
  using Base::final_transformation_;
  using Base::getClassName;
  using Base::indices_;
  using Base::input_;
  using Base::max_iterations_;
  using Base::nr_iterations_;
  using Base::previous_transformation_;
  using Base::reg_name_;
  using Base::target_;
  using Base::transformation_;
  using Base::transformation_epsilon_;
  using Base::transformation_estimation_;
  using Base::transformation_rotation_epsilon_;
  using Base::tree_;
  using Base::update_visualizer_;

  LeastSquaresSurfaceMatching();
  ~LeastSquaresSurfaceMatching() override = default;

  /// \brief Use one of the shipped conjugate-point rules (default LND).
  void
  setConjugateRule(ConjugateRuleType type);
  /// \brief Use any rule, including your own ConjugateRule subclass. Null is ignored (error).
  void
  setConjugateRule(const ConjugateRule::Ptr& rule);
  ConjugateRule::Ptr
  getConjugateRule() const
  {
    return rule_;
  }

  /// \brief Robust estimator (default ZuoEstimator(6)). Null is ignored (error).
  void
  setRobustEstimator(const RobustEstimator::Ptr& estimator);
  RobustEstimator::Ptr
  getRobustEstimator() const
  {
    return estimator_;
  }

  /// \brief A-priori weights P_e (eq. 9): 0 free, +inf fixed, else soft (relative to unit weight).
  void
  setParameterWeights(const Vector7d& weights)
  {
    settings_.apriori_weights = weights;
  }
  /// \brief A-priori values L_e (reduced frame); also switches off apriori_from_guess.
  void
  setParameterValues(const Vector7d& values)
  {
    settings_.apriori_values = values;
    settings_.apriori_from_guess = false;
  }
  /// \brief Preset: 7-parameter similarity, 6-parameter rigid, translation only, height only.
  void
  setParameterModel(ParameterModel model)
  {
    settings_.setParameterModel(model);
  }
  /// \brief Fix (or free) one parameter, e.g. fixParameter(pcl_ls3d::SCALE).
  void
  fixParameter(int index, bool fixed = true)
  {
    settings_.fixParameter(index, fixed);
  }

  /// \brief Convergence threshold on every angle change [rad] (Zuo: 1e-6).
  void
  setAngleEpsilon(double epsilon)
  {
    settings_.angle_epsilon = epsilon;
  }
  /// \brief Regular thinning of source observations: one per voxel of this edge (0 = off).
  void
  setSourceThinning(double voxel_step)
  {
    settings_.source_thinning = voxel_step;
  }
  double
  getSourceThinning() const
  {
    return settings_.source_thinning;
  }

  /// \brief All settings at once; also copies max_iterations and max_correspondence_distance
  ///        into the pcl::Registration members and unsets PCL's transformation and rotation
  ///        epsilons (the settings' own epsilons then rule). Invalid settings are rejected with
  ///        PCL_ERROR and false.
  bool
  setAdjustmentSettings(const AdjustmentSettings& settings);
  /// \brief The settings as the next align() will use them (base-class knobs merged in).
  AdjustmentSettings
  getAdjustmentSettings() const;

  /// \brief As pcl::DefaultConvergenceCriteria::setFailureAfterMaximumIterations: when true,
  ///        hitting the iteration limit leaves hasConverged() false (default false, like ICP).
  void
  setFailureAfterMaximumIterations(bool failure)
  {
    failure_after_max_iter_ = failure;
  }

  /// \brief Report of the last align(): parameters, σ0, σ_i, Qxx, correlation, redundancy, log.
  const AdjustmentReport&
  getReport() const
  {
    return report_;
  }

protected:
  /// \brief The LS3D iteration; called by pcl::Registration::align().
  void
  computeTransformation(PointCloudSource& output, const Matrix4& guess) override;

private:
  /// Finite source points over indices_ (with their cloud indices), thinned by `thinning`.
  void
  collectSourcePoints(double thinning, std::vector<Eigen::Vector3d>& points,
                      std::vector<int>& index_of) const;
  /// Why the inputs cannot be adjusted (empty string when they can); prepares the rule.
  std::string
  checkInputs(const std::vector<Eigen::Vector3d>& points, const TargetSurface& surface,
              ConjugateRule& rule) const;
  /// Below this many finite target points the local-surface rules cannot work.
  static constexpr std::size_t kTinyCloud = 20;
  /// rule_, or for tiny clouds a point-to-point rule (settings.min_observations lowered to fit).
  ConjugateRule::Ptr
  ruleForSize(std::size_t source_points, AdjustmentSettings& settings) const;
  /// True when some source point under `guess` falls into the target's box (10 % margin), or
  /// when the source lies so far away (centres > 2 box diagonals apart) that it is no overlap.
  /// False: the source lies just beside the target, start at the centroids.
  bool
  overlapsTarget(const std::vector<Eigen::Vector3d>& points, const Eigen::Matrix4d& guess) const;
  /// `guess` followed by the translation that moves the source centroid onto the target's.
  Eigen::Matrix4d
  centroidStart(const std::vector<Eigen::Vector3d>& points, const Eigen::Matrix4d& guess) const;
  /// PCL's members (final transformation, convergence, iterations) from report_.
  void
  adoptReport();
  /// As ICP: transformation_ = the last iteration's increment (final = increment × pose before
  /// it), previous_transformation_ = the increment before it (identity when there was none).
  void
  adoptIncrements();
  /// PCL_WARN once per object for each pcl::Registration strategy that LS3D does not use.
  void
  warnIgnoredStrategies();
  /// The engine hooks that carry out PCL's rejectors, fitness epsilon and visualiser callback
  /// over the source points `index_of` (cloud indices) on `surface`.
  IterationHooks
  pclHooks(const std::vector<int>& index_of, const TargetSurface& surface);
  /// The whole input cloud under `pose` (normals rotated too when the type has them), as
  /// ICP's input_transformed.
  void
  transformInput(const Eigen::Matrix4d& pose, PointCloudSource& out) const;
  /// One pcl::Correspondence per observed source point: index_query = its cloud index,
  /// index_match = the target point nearest its conjugate point, distance = squared distance
  /// of the two under `pose` (CorrespondenceEstimation's meaning). first_obs[k] = the first
  /// observation of correspondence k.
  void
  observationCorrespondences(const Eigen::Matrix4d& pose, const ObservationSet& obs,
                             const std::vector<int>& index_of, const TargetSurface& surface,
                             pcl::Correspondences& corr, std::vector<std::size_t>& first_obs) const;
  /// Runs getCorrespondenceRejectors() in order on the observations (as ICP does per iteration).
  void
  rejectObservations(const Eigen::Matrix4d& pose, const ObservationSet& obs, const std::vector<int>& index_of,
                     const TargetSurface& surface, std::vector<char>& keep);

  AdjustmentSettings settings_;
  ConjugateRule::Ptr rule_;
  RobustEstimator::Ptr estimator_;
  AdjustmentReport report_;
  SurfaceMatchingCore core_;
  bool failure_after_max_iter_ = false;
  /// The correspondence estimation pcl::Registration made; another one was set by the user.
  typename Base::CorrespondenceEstimationPtr default_correspondence_estimation_;
  pcl::PCLPointCloud2::Ptr target_blob_;  ///< target for rejectors needing points / normals
  double previous_mse_ = 0.0;             ///< fitness epsilon: the last iteration's MSE
  /// Poses (cloud coordinates) after the last iteration and the two before it (the start
  /// before the first): PCL's incremental transformations are their ratios.
  Eigen::Matrix4d pose_last_ = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d pose_before_ = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d pose_before_that_ = Eigen::Matrix4d::Identity();
  bool warned_estimation_ = false, warned_correspondence_ = false;
};

}  // namespace pcl_ls3d

#ifdef PCL_NO_PRECOMPILE
#include <pcl_ls3d/registration/impl/least_squares_surface_matching.hpp>
#endif
