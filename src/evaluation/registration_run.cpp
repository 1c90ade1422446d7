#include <pcl_ls3d/evaluation/registration_run.h>

#include <pcl/common/time.h>

#include <cmath>
#include <ctime>
#include <exception>

namespace pcl_ls3d {
namespace evaluation {

double
processCpuSeconds()
{
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

RegistrationRun
timedRun(const std::string& name, const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& source,
         const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& target,
         const std::function<void(RegistrationRun&)>& method)
{
  RegistrationRun run;
  run.name = name;
  if (!source || !target || source->empty() || target->empty()) {
    run.message = "empty source or target";
    return run;
  }
  try {
    pcl::StopWatch watch;
    const double cpu0 = processCpuSeconds();
    method(run);
    run.time_s = watch.getTimeSeconds();
    run.cpu_s = processCpuSeconds() - cpu0;
  } catch (const std::exception& e) {
    run.ran = false;
    run.message = std::string("exception: ") + e.what();
  }
  return run;
}

RunEvaluation::RunEvaluation(const CloudXYZ::ConstPtr& source, const CloudXYZ::ConstPtr& target,
                             double max_distance)
    : rms_max_distance(max_distance), source_points(cloudToMatrix(*source))
{
  if (target && !target->empty())
    target_tree.setInputCloud(target);
}

void
RunEvaluation::evaluate(RegistrationRun& run, const Eigen::Matrix4d* truth) const
{
  if (truth)
    run.error = computeTransformError(run.transformation, *truth, source_points);
  run.rms = std::numeric_limits<double>::quiet_NaN();
  run.rms_points = 0;
  if (!run.transformation.allFinite() || !target_tree.getInputCloud())
    return;

  const Eigen::Matrix3d R = run.transformation.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = run.transformation.topRightCorner<3, 1>();
  const double max_sq = rms_max_distance * rms_max_distance;
  double sum_sq = 0.0;
  std::size_t n = 0;
#pragma omp parallel for reduction(+ : sum_sq, n) schedule(static)
  for (Eigen::Index i = 0; i < source_points.cols(); ++i) {
    const Eigen::Vector3d y = R * source_points.col(i) + t;
    pcl::PointXYZ q(static_cast<float>(y.x()), static_cast<float>(y.y()), static_cast<float>(y.z()));
    pcl::Indices k(1);
    std::vector<float> d2(1);
    if (target_tree.nearestKSearch(q, 1, k, d2) == 1 && d2[0] <= max_sq) {
      sum_sq += d2[0];
      ++n;
    }
  }
  run.rms_points = n;
  if (n > 0)
    run.rms = std::sqrt(sum_sq / static_cast<double>(n));
}

}  // namespace evaluation
}  // namespace pcl_ls3d
