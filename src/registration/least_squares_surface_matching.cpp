// Explicit instantiations of LeastSquaresSurfaceMatching for the common point types.
#include <pcl_ls3d/point_types.h>
#include <pcl_ls3d/registration/impl/least_squares_surface_matching.hpp>

#include <pcl/point_types.h>

PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(pcl::PointXYZ, pcl::PointXYZ)
PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(pcl::PointXYZI, pcl::PointXYZI)
PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(pcl::PointNormal, pcl::PointNormal)
PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(pcl_ls3d::PointLiDAR, pcl_ls3d::PointLiDAR)
PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(pcl::PointXYZ, pcl::PointNormal)
PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(pcl::PointNormal, pcl::PointXYZ)
template class PCL_EXPORTS pcl_ls3d::LeastSquaresSurfaceMatching<pcl::PointXYZ, pcl::PointXYZ, double>;
