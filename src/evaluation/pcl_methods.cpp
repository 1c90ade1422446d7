#include <pcl_ls3d/evaluation/pcl_methods.h>

#include <pcl/common/time.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/registration/gicp.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/ndt.h>
#include <pcl/registration/transformation_estimation_svd_scale.h>

#include <cstdio>
#include <type_traits>

namespace pcl_ls3d {
namespace evaluation {

namespace {

using CloudXYZ = pcl::PointCloud<pcl::PointXYZ>;
using CloudNormal = pcl::PointCloud<pcl::PointNormal>;

/// Exposes the protected iteration counter of any pcl::Registration.
template <typename Reg>
class Counted : public Reg
{
public:
  int
  iterations() const
  {
    return this->nr_iterations_;
  }
};

/// Aligns from the identity and fills the run from PCL's own state.
template <typename Reg, typename CloudPtr>
void
alignAndCollect(Reg& reg, const CloudPtr& source, const CloudPtr& target, const PclMethodSettings& s,
                RegistrationRun& run)
{
  reg.setMaximumIterations(s.max_iterations);
  reg.setInputSource(source);
  reg.setInputTarget(target);
  std::remove_const_t<typename CloudPtr::element_type> output;
  reg.align(output);
  run.iterations = reg.iterations();
  run.pcl_converged = reg.hasConverged();
  run.hit_limit = run.iterations >= s.max_iterations;
  run.converged = run.pcl_converged && !run.hit_limit;
  run.transformation = reg.getFinalTransformation().template cast<double>();
  run.ran = true;
  run.message = run.converged ? "converged" : (run.hit_limit ? "iteration limit" : "not converged");
  run.stop = run.converged ? "conv" : (run.hit_limit ? "LIMIT" : "noconv");
  // PCL can report convergence with a NaN transformation (ICP-N on collinear points).
  if (!run.transformation.allFinite()) {
    run.converged = false;
    run.message = "non-finite transformation (hasConverged() " +
                  std::string(run.pcl_converged ? "true" : "false") + ")";
    run.stop = "NaN";
  }
}

/// The stopping rule ICP and ICP-N share (PCL's DefaultConvergenceCriteria).
template <typename Icp>
void
setIcpCriteria(Icp& icp, const PclMethodSettings& s)
{
  icp.setMaxCorrespondenceDistance(s.max_correspondence_distance);
  icp.setTransformationEpsilon(s.transformation_epsilon);
  icp.setTransformationRotationEpsilon(s.rotation_epsilon);
}

void
runIcp(const CloudXYZ::ConstPtr& source, const CloudXYZ::ConstPtr& target, const PclMethodSettings& s,
       bool with_scale, RegistrationRun& run)
{
  Counted<pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>> icp;
  if (with_scale)
    icp.setTransformationEstimation(
        pcl::make_shared<
            pcl::registration::TransformationEstimationSVDScale<pcl::PointXYZ, pcl::PointXYZ>>());
  setIcpCriteria(icp, s);
  alignAndCollect(icp, source, target, s, run);
}

/// x, y, z of `cloud` into a cloud with normals (normals left as they are).
void
copyPositions(const CloudXYZ& cloud, CloudNormal& with_normals)
{
  with_normals.resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    with_normals.points[i].getVector3fMap() = cloud[i].getVector3fMap();
}

void
runIcpNormals(const CloudXYZ::ConstPtr& source, const CloudXYZ::ConstPtr& target, const PclMethodSettings& s,
              RegistrationRun& run)
{
  pcl::StopWatch watch;
  // Target normals only: PCL's point-to-plane objective (TransformationEstimationPointToPlaneLLS)
  // reads the target's normals and ignores the source's, so estimating both would only add time.
  pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::PointNormal> ne(s.threads);
  ne.setInputCloud(target);
  ne.setKSearch(s.normal_k);
  CloudNormal::Ptr target_n(new CloudNormal);
  ne.compute(*target_n);
  copyPositions(*target, *target_n);  // compute() fills only the normal fields
  CloudNormal::Ptr source_n(new CloudNormal);
  copyPositions(*source, *source_n);
  run.normals_time_s = watch.getTimeSeconds();

  Counted<pcl::IterativeClosestPointWithNormals<pcl::PointNormal, pcl::PointNormal>> icp;
  setIcpCriteria(icp, s);
  alignAndCollect(icp, CloudNormal::ConstPtr(source_n), CloudNormal::ConstPtr(target_n), s, run);
}

void
runGicp(const CloudXYZ::ConstPtr& source, const CloudXYZ::ConstPtr& target, const PclMethodSettings& s,
        RegistrationRun& run)
{
  Counted<pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>> gicp;
  gicp.setMaxCorrespondenceDistance(s.max_correspondence_distance);
  gicp.setTransformationEpsilon(s.gicp_translation_epsilon);
  gicp.setRotationEpsilon(s.gicp_rotation_epsilon);
  gicp.setCorrespondenceRandomness(s.gicp_k_correspondences);
  gicp.setTranslationGradientTolerance(s.gicp_gradient_tolerance);
  gicp.setRotationGradientTolerance(s.gicp_gradient_tolerance);
  alignAndCollect(gicp, source, target, s, run);
}

void
runNdt(const CloudXYZ::ConstPtr& source, const CloudXYZ::ConstPtr& target, const PclMethodSettings& s,
       RegistrationRun& run)
{
  Counted<pcl::NormalDistributionsTransform<pcl::PointXYZ, pcl::PointXYZ>> ndt;
  ndt.setResolution(static_cast<float>(s.ndt_resolution));
  ndt.setStepSize(s.ndt_step_size);
  ndt.setOulierRatio(s.ndt_outlier_ratio);
  ndt.setTransformationEpsilon(s.transformation_epsilon);
  alignAndCollect(ndt, source, target, s, run);
}

}  // namespace

std::string
pclMethodName(PclMethod method)
{
  switch (method) {
  case PclMethod::ICP:
    return "PCL-ICP";
  case PclMethod::ICP_NORMALS:
    return "PCL-ICP-N";
  case PclMethod::GICP:
    return "PCL-GICP";
  case PclMethod::NDT:
    return "PCL-NDT";
  case PclMethod::ICP_SCALE:
    return "PCL-ICP-S";
  }
  return "PCL-?";
}

const std::vector<PclMethod>&
allPclMethods()
{
  static const std::vector<PclMethod> all{PclMethod::ICP, PclMethod::ICP_NORMALS, PclMethod::GICP,
                                          PclMethod::NDT};
  return all;
}

std::string
PclMethodSettings::describe(const std::string& unit) const
{
  const char* u = unit.c_str();
  char buf[640];
  std::snprintf(buf, sizeof(buf),
                "max_corr=%g %s, max_iter=%d, ICP/ICP-N/NDT trans_eps=%g %s^2 (squared step), "
                "ICP/ICP-N rot_eps(cos)=1-%.0e, GICP eps=%g %s / %g rad, GICP k=%d grad_tol=%g, "
                "ICP-N normals k=%d (target only, NormalEstimationOMP), NDT res=%g %s step=%g %s "
                "outlier=%g",
                max_correspondence_distance, u, max_iterations, transformation_epsilon, u,
                1.0 - rotation_epsilon, gicp_translation_epsilon, u, gicp_rotation_epsilon,
                gicp_k_correspondences, gicp_gradient_tolerance, normal_k, ndt_resolution, u, ndt_step_size,
                u, ndt_outlier_ratio);
  return buf;
}

PclMethodSettings
PclMethodSettings::inUnit(double metres_per_unit) const
{
  PclMethodSettings s = *this;
  s.max_correspondence_distance /= metres_per_unit;
  s.transformation_epsilon /= metres_per_unit * metres_per_unit;
  s.gicp_translation_epsilon /= metres_per_unit;
  s.ndt_resolution /= metres_per_unit;
  s.ndt_step_size /= metres_per_unit;
  return s;
}

RegistrationRun
runPclMethod(PclMethod method, const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& source,
             const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& target, const PclMethodSettings& settings)
{
  return timedRun(pclMethodName(method), source, target, [&](RegistrationRun& run) {
    switch (method) {
    case PclMethod::ICP:
      runIcp(source, target, settings, false, run);
      break;
    case PclMethod::ICP_SCALE:
      runIcp(source, target, settings, true, run);
      break;
    case PclMethod::ICP_NORMALS:
      runIcpNormals(source, target, settings, run);
      break;
    case PclMethod::GICP:
      runGicp(source, target, settings, run);
      break;
    case PclMethod::NDT:
      runNdt(source, target, settings, run);
      break;
    }
  });
}

}  // namespace evaluation
}  // namespace pcl_ls3d
