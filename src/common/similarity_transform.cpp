#include <pcl_ls3d/common/similarity_transform.h>

#include <Eigen/SVD>

#include <cmath>

namespace pcl_ls3d {

const std::array<std::string, 7>&
similarityParameterNames()
{
  static const std::array<std::string, 7> names{"tx", "ty", "tz", "phi", "omega", "kappa", "m"};
  return names;
}

SimilarityTransform::SimilarityTransform(const Vector7d& p)
    : t(p.head<3>()), phi(p[PHI]), omega(p[OMEGA]), kappa(p[KAPPA]), m(p[SCALE])
{}

Vector7d
SimilarityTransform::vector() const
{
  Vector7d p;
  p << t, phi, omega, kappa, m;
  return p;
}

Eigen::Matrix3d
SimilarityTransform::rotation() const
{
  return (Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(omega, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(kappa, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

Eigen::Matrix4d
SimilarityTransform::matrix() const
{
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = m * rotation();
  T.topRightCorner<3, 1>() = t;
  return T;
}

Eigen::Vector3d
SimilarityTransform::apply(const Eigen::Vector3d& x) const
{
  return t + m * (rotation() * x);
}

SimilarityTransform
SimilarityTransform::inverse() const
{
  Eigen::Matrix4d Ti = Eigen::Matrix4d::Identity();
  const Eigen::Matrix3d Rt = rotation().transpose();
  Ti.topLeftCorner<3, 3>() = Rt / m;
  Ti.topRightCorner<3, 1>() = -(Rt * t) / m;
  return fromMatrix(Ti);
}

SimilarityTransform
SimilarityTransform::fromMatrix(const Eigen::Matrix4d& T)
{
  SimilarityTransform s;
  const Eigen::Matrix3d M = T.topLeftCorner<3, 3>();
  s.m = std::cbrt(M.determinant());
  // Closest rotation to M / m (removes rounding in matrices read from files).
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(M / s.m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  // R = R_Y(φ) R_X(ω) R_Z(κ): R(1,2) = -sin ω, R(0,2) = sin φ cos ω, R(2,2) = cos φ cos ω,
  // R(1,0) = cos ω sin κ, R(1,1) = cos ω cos κ.
  s.omega = std::asin(std::max(-1.0, std::min(1.0, -R(1, 2))));
  s.phi = std::atan2(R(0, 2), R(2, 2));
  s.kappa = std::atan2(R(1, 0), R(1, 1));
  s.t = T.topRightCorner<3, 1>();
  return s;
}

Eigen::Matrix4d
localToGlobal(const Eigen::Matrix4d& T_local, const Eigen::Vector3d& origin_source,
              const Eigen::Vector3d& origin_target)
{
  Eigen::Matrix4d T = T_local;
  // x_t = o_t + A (x_s - o_s) + b  =>  b' = o_t + b - A o_s
  T.topRightCorner<3, 1>() =
      origin_target + T_local.topRightCorner<3, 1>() - T_local.topLeftCorner<3, 3>() * origin_source;
  return T;
}

Eigen::Matrix4d
globalToLocal(const Eigen::Matrix4d& T_global, const Eigen::Vector3d& origin_source,
              const Eigen::Vector3d& origin_target)
{
  Eigen::Matrix4d T = T_global;
  T.topRightCorner<3, 1>() =
      T_global.topRightCorner<3, 1>() - origin_target + T_global.topLeftCorner<3, 3>() * origin_source;
  return T;
}

}  // namespace pcl_ls3d
