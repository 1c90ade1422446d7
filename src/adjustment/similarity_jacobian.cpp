#include <pcl_ls3d/adjustment/similarity_jacobian.h>

#include <cmath>

namespace pcl_ls3d {

namespace {
// Elementary rotations and their derivatives, R = R_Y(φ) R_X(ω) R_Z(κ).
Eigen::Matrix3d
rotY(double a, bool derivative)
{
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d R;
  if (derivative)
    R << -s, 0, c, 0, 0, 0, -c, 0, -s;
  else
    R << c, 0, s, 0, 1, 0, -s, 0, c;
  return R;
}
Eigen::Matrix3d
rotX(double a, bool derivative)
{
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d R;
  if (derivative)
    R << 0, 0, 0, 0, -s, -c, 0, c, -s;
  else
    R << 1, 0, 0, 0, c, -s, 0, s, c;
  return R;
}
Eigen::Matrix3d
rotZ(double a, bool derivative)
{
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d R;
  if (derivative)
    R << -s, -c, 0, c, -s, 0, 0, 0, 0;
  else
    R << c, -s, 0, s, c, 0, 0, 0, 1;
  return R;
}
}  // namespace

SimilarityLinearization::SimilarityLinearization(const SimilarityTransform& X) : t_(X.t)
{
  const Eigen::Matrix3d Ry = rotY(X.phi, false), Rx = rotX(X.omega, false);
  const Eigen::Matrix3d Rz = rotZ(X.kappa, false);
  R_ = Ry * Rx * Rz;
  mR_ = X.m * R_;
  mdR_phi_ = X.m * rotY(X.phi, true) * Rx * Rz;
  mdR_omega_ = X.m * Ry * rotX(X.omega, true) * Rz;
  mdR_kappa_ = X.m * Ry * Rx * rotZ(X.kappa, true);
}

Matrix37d
SimilarityLinearization::jacobian(const Eigen::Vector3d& x) const
{
  Matrix37d J;
  J.leftCols<3>().setIdentity();
  J.col(PHI) = mdR_phi_ * x;
  J.col(OMEGA) = mdR_omega_ * x;
  J.col(KAPPA) = mdR_kappa_ * x;
  J.col(SCALE) = R_ * x;
  return J;
}

RowVector7d
SimilarityLinearization::designRow(const Eigen::Vector3d& u, const Eigen::Vector3d& x) const
{
  RowVector7d a;
  a.head<3>() = u.transpose();
  a[PHI] = u.dot(mdR_phi_ * x);
  a[OMEGA] = u.dot(mdR_omega_ * x);
  a[KAPPA] = u.dot(mdR_kappa_ * x);
  a[SCALE] = u.dot(R_ * x);
  return a;
}

Vector7d
rankTestScaling(double radius)
{
  const double inv_r = radius > 0.0 ? 1.0 / radius : 1.0;
  Vector7d scaling;
  scaling << 1, 1, 1, inv_r, inv_r, inv_r, inv_r;
  return scaling;
}

}  // namespace pcl_ls3d
