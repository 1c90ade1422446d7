#include <pcl_ls3d/evaluation/transform_error.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace evaluation {

namespace {

/// Wraps an angle difference to (−π, π].
double
wrapAngle(double a)
{
  a = std::remainder(a, 2.0 * M_PI);  // in [−π, π]
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

}  // namespace

double
displacementError(const Eigen::Matrix4d& T_est, const Eigen::Matrix4d& T_true, const Eigen::Vector3d& x)
{
  // (T_est − T_true) applied to [x; 1]: one product instead of two transforms.
  const Eigen::Matrix<double, 3, 4> D = (T_est - T_true).topRows<3>();
  return (D.leftCols<3>() * x + D.col(3)).norm();
}

Vector7d
parameterErrors(const Eigen::Matrix4d& T_est, const Eigen::Matrix4d& T_true)
{
  Vector7d e =
      SimilarityTransform::fromMatrix(T_est).vector() - SimilarityTransform::fromMatrix(T_true).vector();
  for (int i = PHI; i <= KAPPA; ++i)
    e[i] = wrapAngle(e[i]);
  return e;
}

TransformError
computeTransformError(const Eigen::Matrix4d& T_est, const Eigen::Matrix4d& T_true,
                      const Eigen::Matrix3Xd& source_points)
{
  TransformError out;
  if (!T_est.allFinite() || !T_true.allFinite())
    return out;

  const Eigen::Matrix<double, 3, 4> D = (T_est - T_true).topRows<3>();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  double sum = 0.0, sum_sq = 0.0, max = 0.0;
  std::size_t n = 0;
  for (Eigen::Index i = 0; i < source_points.cols(); ++i) {
    const Eigen::Vector3d x = source_points.col(i);
    if (!x.allFinite())
      continue;
    const double d = (D.leftCols<3>() * x + D.col(3)).norm();
    sum += d;
    sum_sq += d * d;
    max = std::max(max, d);
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
    ++n;
  }
  if (n == 0)
    return out;

  double max_bbox = 0.0;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(),
                                 (c & 4) ? hi.z() : lo.z());
    max_bbox = std::max(max_bbox, (D.leftCols<3>() * corner + D.col(3)).norm());
  }

  out.points = n;
  out.mean = sum / static_cast<double>(n);
  out.rms = std::sqrt(sum_sq / static_cast<double>(n));
  out.max = max;
  out.max_bbox = max_bbox;
  out.parameters = parameterErrors(T_est, T_true);
  out.valid = true;
  return out;
}

}  // namespace evaluation
}  // namespace pcl_ls3d
