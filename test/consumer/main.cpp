// Links against the installed library and checks one computed value, so a broken install
// (missing symbols, wrong headers) fails here rather than in a user's project.
#include <pcl_ls3d/common/similarity_transform.h>
#include <pcl_ls3d/point_types.h>

#include <pcl/point_cloud.h>

#include <cmath>
#include <iostream>

int
main()
{
  pcl_ls3d::SimilarityTransform s;
  s.kappa = M_PI / 2;
  s.t = Eigen::Vector3d(1, 0, 0);
  const Eigen::Vector3d y = s.apply(Eigen::Vector3d(1, 0, 0));
  pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
  cloud.push_back(pcl_ls3d::PointLiDAR(1.f, 2.f, 3.f));
  if ((y - Eigen::Vector3d(1, 1, 0)).norm() > 1e-12 || cloud.size() != 1) {
    std::cerr << "consumer: unexpected result\n";
    return 1;
  }
  std::cout << "consumer: pcl_ls3d found and linked\n";
  return 0;
}
