#pragma once
/// \file sac_model_surface_matching.h
/// \brief Surface matching as a PCL sample-consensus model (Li et al. 2001: LMS is a search over
///        minimal subsets, not a weight function), so that pcl::LeastMedianSquares, pcl::RandomSampleConsensus
///        and pcl::MEstimatorSampleConsensus drive it unchanged:
/// \code
///   using Model = pcl_ls3d::SampleConsensusModelSurfaceMatching<pcl::PointXYZ>;
///   Model::Ptr model(new Model(epoch, reference));   // LHD: LZD rule, 6 parameters
///   model->linearize(start);                         // e.g. an all-points LHD result
///   pcl::LeastMedianSquares<pcl::PointXYZ> lmeds(model, 3.0 * sigma);
///   lmeds.setMaxIterations(3000);                    // m subsets (Li eq. 12)
///   lmeds.computeModel();
///   Eigen::VectorXf c; lmeds.getModelCoefficients(c);
///   Eigen::Matrix4d T = model->toMatrix(c);          // EPOCH -> REFERENCE
/// \endcode
///
/// The input cloud is the epoch (Li's "mate" surface S'), the points that are sampled; the
/// reference surface S is given to the constructor. Model coefficients are the 7 similarity
/// parameters (tx, ty, tz, φ, ω, κ, m) in the reduced frame of the model's LinearizedMatching
/// (origins in getLinearization().block()); m stays 1 and the other fixed parameters at their
/// start values under the 6-parameter (rigid, default) or other parameter models.
///  - computeModelCoefficients: LHD of the sampled epoch points onto the reference: the engine's
///    Gauss–Markoff solve over their design rows (one Gauss–Newton step from the linearisation
///    point); fails when the sample leaves a parameter undeterminable.
///  - getDistancesToModel: |v_j| = |l_j + a_j (X − X0)| of every epoch point in indices_, the
///    linearised residual along the rule's direction (vertical for LZD); +inf where the point
///    has no conjugate on the reference.
///  - optimizeModelCoefficients: IRLS refinement with Tukey's biweight (c = 4.685, MAD scale) in
///    the engine's own adjustment loop over the inliers, conjugate points re-matched every
///    iteration (nonlinear).
///  - getModelType(): pcl::SACMODEL_REGISTRATION.
/// Call linearize() again after a search whose estimate moved far from the linearisation point
/// (the residuals are first-order in X − X0); estimators/robust_matching.h does this.

#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/rules/conjugate_rule.h>
#include <pcl_ls3d/sample_consensus/linearized_matching.h>

#include <pcl/sample_consensus/sac_model.h>
#include <pcl/search/kdtree.h>

#include <memory>

namespace pcl_ls3d {

/// \brief Surface matching of an epoch cloud onto a reference surface as a SAC model.
template <typename PointT>
class SampleConsensusModelSurfaceMatching : public pcl::SampleConsensusModel<PointT>
{
public:
  using Base = pcl::SampleConsensusModel<PointT>;
  using PointCloud = typename Base::PointCloud;
  using PointCloudConstPtr = typename Base::PointCloudConstPtr;
  using Ptr = std::shared_ptr<SampleConsensusModelSurfaceMatching<PointT>>;
  using ConstPtr = std::shared_ptr<const SampleConsensusModelSurfaceMatching<PointT>>;
  using Base::error_sqr_dists_;
  using Base::indices_;
  using Base::input_;
  using Base::model_name_;
  using Base::model_size_;
  using Base::sample_size_;
  using Base::shuffled_indices_;

  /// \param[in] epoch the cloud to sample (Li's mate surface S')
  /// \param[in] reference the reference surface S (a kd-tree is built on it)
  /// \param[in] random seed the sampler from the clock (as every PCL SAC model)
  /// Linearises at the identity with the LZD rule and 6 parameters (LHD).
  SampleConsensusModelSurfaceMatching(const PointCloudConstPtr& epoch, const PointCloudConstPtr& reference,
                                      bool random = false);
  SampleConsensusModelSurfaceMatching(const PointCloudConstPtr& epoch, const pcl::Indices& indices,
                                      const PointCloudConstPtr& reference, bool random = false);
  ~SampleConsensusModelSurfaceMatching() override = default;

  /// \brief Rule, parameter model and the other adjustment settings; re-linearises at the
  ///        current start. False (PCL_ERROR) on invalid settings or when nothing overlaps.
  bool
  setMatching(const ConjugateRule::Ptr& rule, const AdjustmentSettings& settings);
  /// \brief Points per sample (p ≥ the free parameters; Li: 7 for 6). False when too small.
  bool
  setSampleSize(unsigned int p);
  /// \brief Matches every epoch point at `start` (EPOCH → REFERENCE, cloud coordinates) and
  ///        linearises there. The model's indices become those of the given indices (all points
  ///        by default) whose point found a conjugate: PCL's estimators take the median over
  ///        getIndices(), and points that cannot be observed must not shift its quantile.
  ///        False (PCL_ERROR) when no epoch point finds a conjugate.
  bool
  linearize(const Eigen::Matrix4d& start);

  /// The model coefficients of a 4×4 EPOCH → REFERENCE transformation (cloud coordinates).
  Eigen::VectorXf
  toCoefficients(const Eigen::Matrix4d& T) const;
  /// The 4×4 EPOCH → REFERENCE transformation (cloud coordinates) of model coefficients.
  Eigen::Matrix4d
  toMatrix(const Eigen::VectorXf& model_coefficients) const;
  /// The observations, rows and frames behind the model.
  const LinearizedMatching&
  getLinearization() const
  {
    return *lin_;
  }
  /// Signed linearised residuals v_j of every epoch point in indices_ (NaN: no conjugate).
  void
  getResidualsToModel(const Eigen::VectorXf& model_coefficients, std::vector<double>& residuals) const;

  // ---- pcl::SampleConsensusModel ----------------------------------------------------------
  bool
  computeModelCoefficients(const pcl::Indices& samples, Eigen::VectorXf& model_coefficients) const override;
  void
  optimizeModelCoefficients(const pcl::Indices& inliers, const Eigen::VectorXf& model_coefficients,
                            Eigen::VectorXf& optimized_coefficients) const override;
  void
  getDistancesToModel(const Eigen::VectorXf& model_coefficients,
                      std::vector<double>& distances) const override;
  void
  selectWithinDistance(const Eigen::VectorXf& model_coefficients, const double threshold,
                       pcl::Indices& inliers) override;
  std::size_t
  countWithinDistance(const Eigen::VectorXf& model_coefficients, const double threshold) const override;
  /// Moves the inliers into the reference frame and onto the reference surface along the rule's
  /// direction (the point minus v u / |u|²).
  void
  projectPoints(const pcl::Indices& inliers, const Eigen::VectorXf& model_coefficients,
                PointCloud& projected_points, bool copy_data_fields = true) const override;
  bool
  doSamplesVerifyModel(const std::set<pcl::index_t>& indices, const Eigen::VectorXf& model_coefficients,
                       const double threshold) const override;
  pcl::SacModel
  getModelType() const override
  {
    return pcl::SACMODEL_REGISTRATION;
  }

protected:
  bool
  isModelValid(const Eigen::VectorXf& model_coefficients) const override;
  bool
  isSampleGood(const pcl::Indices& samples) const override;

private:
  void
  setUp(const PointCloudConstPtr& reference);
  Vector7d
  parameters(const Eigen::VectorXf& model_coefficients) const;
  /// |v| of epoch point `index` (+inf: no conjugate).
  double
  distanceOf(pcl::index_t index, const Vector7d& X) const;

  PointCloudConstPtr reference_;
  typename pcl::search::KdTree<PointT>::Ptr tree_;
  std::shared_ptr<PclTargetSurface<PointT>> surface_;
  ConjugateRule::Ptr rule_;
  AdjustmentSettings settings_;
  std::vector<Eigen::Vector3d> points_;  ///< every epoch point (NaN where not finite)
  pcl::Indices requested_;               ///< the indices given at construction (all by default)
  Eigen::Matrix4d start_ = Eigen::Matrix4d::Identity();
  std::shared_ptr<LinearizedMatching> lin_;
  bool linearized_ = false;
};

}  // namespace pcl_ls3d

#ifdef PCL_NO_PRECOMPILE
#include <pcl_ls3d/sample_consensus/impl/sac_model_surface_matching.hpp>
#endif
