#include <pcl_ls3d/evaluation/ls3d_method.h>
#include <pcl_ls3d/registration/least_squares_surface_matching.h>

#include <cstdio>
#include <limits>

namespace pcl_ls3d {
namespace evaluation {

std::string
ls3dMethodName(ConjugateRuleType rule)
{
  switch (rule) {
  case ConjugateRuleType::LND:
    return "LS3D-LND";
  case ConjugateRuleType::LZD:
    return "LS3D-LZD";
  case ConjugateRuleType::ICP:
    return "LS3D-ICP";
  }
  return "LS3D-?";
}

std::string
Ls3dMethodSettings::describe(const std::string& unit) const
{
  const char* u = unit.c_str();
  char corr[64], iter[32];
  if (max_correspondence_distance > 0.0)
    std::snprintf(corr, sizeof(corr), "%g %s", max_correspondence_distance, u);
  else
    std::snprintf(corr, sizeof(corr), "default (automatic reach)");
  if (max_iterations > 0)
    std::snprintf(iter, sizeof(iter), "%d", max_iterations);
  else
    std::snprintf(iter, sizeof(iter), "default");
  char buf[400];
  std::snprintf(buf, sizeof(buf),
                "max_corr=%s, max_iter=%s, thinning=%g %s, angle_eps=1e-6 rad, trans_eps=%g %s, "
                "%s, Zuo 0/1 weight at 6 sigma0, quality gate on",
                corr, iter, source_thinning, u, translation_epsilon, u,
                model == ParameterModel::SIMILARITY_7 ? "7 parameters (similarity)"
                : model == ParameterModel::RIGID_6    ? "6 parameters (rigid)"
                                                      : "reduced parameter model");
  return buf;
}

Ls3dMethodSettings
Ls3dMethodSettings::inUnit(double metres_per_unit) const
{
  Ls3dMethodSettings s = *this;
  if (s.max_correspondence_distance > 0.0)
    s.max_correspondence_distance /= metres_per_unit;
  s.source_thinning /= metres_per_unit;
  s.translation_epsilon /= metres_per_unit;
  return s;
}

namespace {

/// The run as LS3D's report states it; a refused estimate is a row without a transformation.
void
collectReport(LeastSquaresSurfaceMatching<pcl::PointXYZ, pcl::PointXYZ>& ls3d, RegistrationRun& run)
{
  const AdjustmentReport& report = ls3d.getReport();
  run.ran = true;
  run.iterations = report.iterations;
  run.pcl_converged = ls3d.hasConverged();
  run.quality_checked = true;
  run.converged = report.termination == TerminationType::CONVERGED;
  run.hit_limit = report.termination == TerminationType::MAX_ITERATIONS;
  run.stop = terminationTypeToString(report.termination);
  run.sigma0 = report.isSolutionUsable() ? report.sigma0 : std::numeric_limits<double>::quiet_NaN();
  // No estimate (e.g. TOO_FEW_OBSERVATIONS): no transformation either, so the RMS and the
  // errors vs truth read "-" rather than those of the identity (a perfect run for no motion).
  run.transformation = !report.hasEstimate() ? kNoTransformation
                       : report.isSolutionUsable()
                           ? report.transformation
                           : Eigen::Matrix4d(ls3d.getFinalTransformation().cast<double>());
  run.message = terminationTypeToString(report.termination);
  if (!report.message.empty())
    run.message += ": " + report.message;
}

}  // namespace

RegistrationRun
runLs3d(ConjugateRuleType rule, const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& source,
        const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& target, const Ls3dMethodSettings& settings)
{
  return timedRun(ls3dMethodName(rule), source, target, [&](RegistrationRun& run) {
    LeastSquaresSurfaceMatching<pcl::PointXYZ, pcl::PointXYZ> ls3d;
    ls3d.setConjugateRule(rule);
    ls3d.setParameterModel(settings.model);
    if (settings.max_correspondence_distance > 0.0)
      ls3d.setMaxCorrespondenceDistance(settings.max_correspondence_distance);
    if (settings.max_iterations > 0)
      ls3d.setMaximumIterations(settings.max_iterations);
    ls3d.setSourceThinning(settings.source_thinning);
    // The translation epsilon alone (PCL's setTransformationEpsilon would also set the angle's).
    AdjustmentSettings adjustment = ls3d.getAdjustmentSettings();
    adjustment.translation_epsilon = settings.translation_epsilon;
    ls3d.setAdjustmentSettings(adjustment);
    ls3d.setInputSource(source);
    ls3d.setInputTarget(target);
    pcl::PointCloud<pcl::PointXYZ> output;
    ls3d.align(output);
    collectReport(ls3d, run);
  });
}

}  // namespace evaluation
}  // namespace pcl_ls3d
