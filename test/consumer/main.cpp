// Links against the installed library and checks computed values, so a broken install (missing
// symbols, wrong headers, a template instantiation that was not exported) fails here rather
// than in a user's project. It uses LS3D the way a downstream project would: through a
// pcl::Registration base pointer, on clouds it builds itself with a known shift.
#include <pcl_ls3d/common/similarity_transform.h>
#include <pcl_ls3d/point_types.h>
#include <pcl_ls3d/registration/least_squares_surface_matching.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <iostream>
#include <memory>

namespace {

/// A smooth surface with relief in both directions, so all translations are determined.
float
height(float x, float y)
{
  return 2.0f * std::sin(x / 7.0f) + 1.5f * std::cos(y / 9.0f) + 0.02f * x;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr
grid(float spacing, float offset, const Eigen::Vector3f& shift)
{
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (float x = offset; x < 60.0f; x += spacing)
    for (float y = offset; y < 60.0f; y += spacing)
      cloud->push_back(pcl::PointXYZ(x + shift.x(), y + shift.y(), height(x, y) + shift.z()));
  return cloud;
}

}  // namespace

int
main()
{
  pcl_ls3d::SimilarityTransform s;
  s.kappa = M_PI / 2;
  s.t = Eigen::Vector3d(1, 0, 0);
  const Eigen::Vector3d y = s.apply(Eigen::Vector3d(1, 0, 0));
  pcl::PointCloud<pcl_ls3d::PointLiDAR> lidar;
  lidar.push_back(pcl_ls3d::PointLiDAR(1.f, 2.f, 3.f));
  if ((y - Eigen::Vector3d(1, 1, 0)).norm() > 1e-12 || lidar.size() != 1) {
    std::cerr << "consumer: unexpected similarity result\n";
    return 1;
  }

  // Target on a 0.5 m grid; source on an offset 1 m grid of the same surface moved by `shift`.
  // Registering source onto target must return the inverse shift.
  const Eigen::Vector3f shift(0.3f, -0.2f, 0.15f);
  const auto target = grid(0.5f, 0.0f, Eigen::Vector3f::Zero());
  const auto source = grid(1.0f, 5.25f, shift);
  std::unique_ptr<pcl::Registration<pcl::PointXYZ, pcl::PointXYZ>> reg(
      new pcl_ls3d::LeastSquaresSurfaceMatching<pcl::PointXYZ, pcl::PointXYZ>());
  reg->setInputSource(source);
  reg->setInputTarget(target);
  pcl::PointCloud<pcl::PointXYZ> aligned;
  reg->align(aligned);
  const Eigen::Vector3f t = reg->getFinalTransformation().block<3, 1>(0, 3);
  // No noise: only the surface interpolation error remains; 1 cm is 15x below the shift.
  if (!reg->hasConverged() || (t + shift).norm() > 0.01f) {
    std::cerr << "consumer: LS3D did not recover the shift (converged " << reg->hasConverged()
              << ", t = " << t.transpose() << ")\n";
    return 1;
  }
  std::cout << "consumer: pcl_ls3d found, linked, LS3D recovered t = " << t.transpose() << "\n";
  return 0;
}
