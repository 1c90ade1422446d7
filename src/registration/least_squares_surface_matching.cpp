// Explicit instantiations of LeastSquaresSurfaceMatching for the common point types.
// PointLiDAR is not one of PCL's precompiled types: PCL_NO_PRECOMPILE pulls in PCL's template
// implementations, and the PCL classes the registration needs are instantiated for it here, so
// users of LeastSquaresSurfaceMatching<PointLiDAR, PointLiDAR> link without extra steps.
#define PCL_NO_PRECOMPILE
#include <pcl_ls3d/point_types.h>
#include <pcl_ls3d/registration/impl/least_squares_surface_matching.hpp>

#include <pcl/impl/pcl_base.hpp>
#include <pcl/kdtree/impl/kdtree_flann.hpp>
#include <pcl/point_types.h>
#include <pcl/search/impl/kdtree.hpp>

template class PCL_EXPORTS pcl::PCLBase<pcl_ls3d::PointLiDAR>;
template class PCL_EXPORTS pcl::KdTreeFLANN<pcl_ls3d::PointLiDAR>;
template class PCL_EXPORTS pcl::search::KdTree<pcl_ls3d::PointLiDAR>;

PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(pcl::PointXYZ, pcl::PointXYZ)
    PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(pcl::PointXYZI, pcl::PointXYZI)
        PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(pcl::PointXYZRGB, pcl::PointXYZRGB)
            PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(pcl::PointNormal, pcl::PointNormal)
                PCL_LS3D_INSTANTIATE_LeastSquaresSurfaceMatching(pcl_ls3d::PointLiDAR, pcl_ls3d::PointLiDAR)
    // Mixed source/target types (e.g. PointXYZ -> PointNormal) are not instantiated: PCL 1.13's own
    // Registration::initCompute() does not compile for them (reciprocal kd-tree type mismatch).
    template class PCL_EXPORTS pcl_ls3d::LeastSquaresSurfaceMatching<pcl::PointXYZ, pcl::PointXYZ, double>;
template class PCL_EXPORTS pcl_ls3d::LeastSquaresSurfaceMatching<pcl::PointXYZI, pcl::PointXYZI, double>;
template class PCL_EXPORTS pcl_ls3d::LeastSquaresSurfaceMatching<pcl::PointNormal, pcl::PointNormal, double>;
