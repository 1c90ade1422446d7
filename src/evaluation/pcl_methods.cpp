#include <pcl_ls3d/evaluation/pcl_methods.h>

#include <pcl/common/time.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/registration/gicp.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/ndt.h>
#include <pcl/registration/transformation_estimation_svd_scale.h>

#include <cstdio>
#include <exception>

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

/// Common tail: align from the identity, fill the run.
template <typename Reg, typename CloudT>
void
alignAndCollect(Reg& reg, CloudT& output, const PclMethodSettings& s, RegistrationRun& run)
{
  reg.align(output);
  run.iterations = reg.iterations();
  run.pcl_converged = reg.hasConverged();
  run.hit_limit = run.iterations >= s.max_iterations;
  run.converged = run.pcl_converged && !run.hit_limit;
  run.transformation = reg.getFinalTransformation().template cast<double>();
  run.ran = true;
  run.message = run.converged ? "converged"
                              : (run.hit_limit ? "iteration limit" : "not converged");
  run.stop = run.converged ? "conv" : (run.hit_limit ? "LIMIT" : "noconv");
  // PCL can report convergence with a NaN transformation (ICP-N on collinear points).
  if (!run.transformation.allFinite()) {
    run.converged = false;
    run.message = "non-finite transformation (hasConverged() " +
                  std::string(run.pcl_converged ? "true" : "false") + ")";
    run.stop = "NaN";
  }
}

void
runIcp(const CloudXYZ::ConstPtr& source, const CloudXYZ::ConstPtr& target,
       const PclMethodSettings& s, bool with_scale, RegistrationRun& run)
{
  pcl::StopWatch watch;
  const double cpu0 = processCpuSeconds();
  Counted<pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>> icp;
  if (with_scale)
    icp.setTransformationEstimation(
        pcl::make_shared<pcl::registration::TransformationEstimationSVDScale<pcl::PointXYZ,
                                                                            pcl::PointXYZ>>());
  icp.setMaxCorrespondenceDistance(s.max_correspondence_distance);
  icp.setMaximumIterations(s.max_iterations);
  icp.setTransformationEpsilon(s.transformation_epsilon);
  icp.setTransformationRotationEpsilon(s.rotation_epsilon);
  icp.setInputSource(source);
  icp.setInputTarget(target);
  CloudXYZ output;
  alignAndCollect(icp, output, s, run);
  run.time_s = watch.getTimeSeconds();
  run.cpu_s = processCpuSeconds() - cpu0;
}

void
runIcpNormals(const CloudXYZ::ConstPtr& source, const CloudXYZ::ConstPtr& target,
              const PclMethodSettings& s, RegistrationRun& run)
{
  pcl::StopWatch watch;
  const double cpu0 = processCpuSeconds();
  // Target normals only: PCL's point-to-plane objective (TransformationEstimationPointToPlaneLLS)
  // reads the target's normals and ignores the source's, so estimating both would only add time.
  pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::PointNormal> ne(s.threads);
  ne.setInputCloud(target);
  ne.setKSearch(s.normal_k);
  CloudNormal::Ptr target_n(new CloudNormal);
  ne.compute(*target_n);
  for (std::size_t i = 0; i < target->size(); ++i)  // compute() fills only the normal fields
    target_n->points[i].getVector3fMap() = (*target)[i].getVector3fMap();
  CloudNormal::Ptr source_n(new CloudNormal);
  source_n->resize(source->size());
  for (std::size_t i = 0; i < source->size(); ++i)
    source_n->points[i].getVector3fMap() = (*source)[i].getVector3fMap();
  run.normals_time_s = watch.getTimeSeconds();

  Counted<pcl::IterativeClosestPointWithNormals<pcl::PointNormal, pcl::PointNormal>> icp;
  icp.setMaxCorrespondenceDistance(s.max_correspondence_distance);
  icp.setMaximumIterations(s.max_iterations);
  icp.setTransformationEpsilon(s.transformation_epsilon);
  icp.setTransformationRotationEpsilon(s.rotation_epsilon);
  icp.setInputSource(source_n);
  icp.setInputTarget(target_n);
  CloudNormal output;
  alignAndCollect(icp, output, s, run);
  run.time_s = watch.getTimeSeconds();
  run.cpu_s = processCpuSeconds() - cpu0;
}

void
runGicp(const CloudXYZ::ConstPtr& source, const CloudXYZ::ConstPtr& target,
        const PclMethodSettings& s, RegistrationRun& run)
{
  pcl::StopWatch watch;
  const double cpu0 = processCpuSeconds();
  Counted<pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>> gicp;
  gicp.setMaxCorrespondenceDistance(s.max_correspondence_distance);
  gicp.setMaximumIterations(s.max_iterations);
  gicp.setTransformationEpsilon(s.gicp_translation_epsilon);
  gicp.setRotationEpsilon(s.gicp_rotation_epsilon);
  gicp.setCorrespondenceRandomness(s.gicp_k_correspondences);
  gicp.setTranslationGradientTolerance(s.gicp_gradient_tolerance);
  gicp.setRotationGradientTolerance(s.gicp_gradient_tolerance);
  gicp.setInputSource(source);
  gicp.setInputTarget(target);
  CloudXYZ output;
  alignAndCollect(gicp, output, s, run);
  run.time_s = watch.getTimeSeconds();
  run.cpu_s = processCpuSeconds() - cpu0;
}

void
runNdt(const CloudXYZ::ConstPtr& source, const CloudXYZ::ConstPtr& target,
       const PclMethodSettings& s, RegistrationRun& run)
{
  pcl::StopWatch watch;
  const double cpu0 = processCpuSeconds();
  Counted<pcl::NormalDistributionsTransform<pcl::PointXYZ, pcl::PointXYZ>> ndt;
  ndt.setResolution(static_cast<float>(s.ndt_resolution));
  ndt.setStepSize(s.ndt_step_size);
  ndt.setOulierRatio(s.ndt_outlier_ratio);
  ndt.setMaximumIterations(s.max_iterations);
  ndt.setTransformationEpsilon(s.transformation_epsilon);
  ndt.setInputSource(source);
  ndt.setInputTarget(target);
  CloudXYZ output;
  alignAndCollect(ndt, output, s, run);
  run.time_s = watch.getTimeSeconds();
  run.cpu_s = processCpuSeconds() - cpu0;
}

}  // namespace

std::string
pclMethodName(PclMethod method)
{
  switch (method) {
  case PclMethod::ICP: return "PCL-ICP";
  case PclMethod::ICP_NORMALS: return "PCL-ICP-N";
  case PclMethod::GICP: return "PCL-GICP";
  case PclMethod::NDT: return "PCL-NDT";
  case PclMethod::ICP_SCALE: return "PCL-ICP-S";
  }
  return "PCL-?";
}

const std::vector<PclMethod>&
allPclMethods()
{
  static const std::vector<PclMethod> all{PclMethod::ICP, PclMethod::ICP_NORMALS,
                                          PclMethod::GICP, PclMethod::NDT};
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
                gicp_k_correspondences, gicp_gradient_tolerance, normal_k, ndt_resolution, u,
                ndt_step_size, u, ndt_outlier_ratio);
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
             const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& target,
             const PclMethodSettings& settings)
{
  RegistrationRun run;
  run.name = pclMethodName(method);
  if (!source || !target || source->empty() || target->empty()) {
    run.message = "empty source or target";
    return run;
  }
  try {
    switch (method) {
    case PclMethod::ICP: runIcp(source, target, settings, false, run); break;
    case PclMethod::ICP_SCALE: runIcp(source, target, settings, true, run); break;
    case PclMethod::ICP_NORMALS: runIcpNormals(source, target, settings, run); break;
    case PclMethod::GICP: runGicp(source, target, settings, run); break;
    case PclMethod::NDT: runNdt(source, target, settings, run); break;
    }
  }
  catch (const std::exception& e) {
    run.ran = false;
    run.message = std::string("exception: ") + e.what();
  }
  return run;
}

}  // namespace evaluation
}  // namespace pcl_ls3d
