#include <pcl_ls3d/evaluation/robust_method.h>

#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/search/flann_kd_tree.h>

#include <pcl/search/kdtree.h>

#include <algorithm>
#include <cctype>
#include <limits>

namespace pcl_ls3d {
namespace evaluation {

std::string
robustMethodName(RobustMethod method)
{
  std::string name = toString(method);
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return "ROBUST-" + name;
}

namespace {

/// The run as the robust matching's report states it; no usable estimate, no transformation.
void
collectReport(const RobustMatchingReport& r, RegistrationRun& run)
{
  run.ran = true;
  run.iterations = r.adjustment.iterations;
  run.converged = r.termination == TerminationType::CONVERGED;
  run.pcl_converged = run.converged;
  run.quality_checked = true;
  run.hit_limit = r.termination == TerminationType::MAX_ITERATIONS;
  run.stop = terminationTypeToString(r.termination);
  run.sigma0 = r.isSolutionUsable() ? r.scale : std::numeric_limits<double>::quiet_NaN();
  run.transformation = r.isSolutionUsable() ? r.adjustment.transformation : kNoTransformation;
  run.message = r.estimator + ": " + terminationTypeToString(r.termination);
  if (!r.message.empty())
    run.message += ": " + r.message;
}

}  // namespace

RegistrationRun
runRobust(RobustMethod method, const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& source,
          const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& target)
{
  return timedRun(robustMethodName(method), source, target, [&](RegistrationRun& run) {
    pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl_ls3d::search::FlannKdTree<pcl::PointXYZ>);
    tree->setInputCloud(target);
    const PclTargetSurface<pcl::PointXYZ> surface(target, tree);
    const ConjugateRule::Ptr rule = makeConjugateRule(ConjugateRuleType::LZD);
    std::string why;
    if (!rule->prepare(surface, &why)) {
      run.message = "LZD rule: " + why;
      return;
    }
    std::vector<Eigen::Vector3d> points;
    points.reserve(source->size());
    for (const auto& p : *source)
      points.push_back(p.getVector3fMap().cast<double>());
    RobustMatchingSettings settings;
    settings.method = method;
    collectReport(robustMatching(points, {}, surface, *rule, settings, Eigen::Matrix4d::Identity()), run);
  });
}

}  // namespace evaluation
}  // namespace pcl_ls3d
