// Explicit instantiations of FlannKdTree for the point types the library instantiates.
#define PCL_NO_PRECOMPILE
#include <pcl_ls3d/point_types.h>
#include <pcl_ls3d/search/impl/flann_kd_tree.hpp>

#include <pcl/point_types.h>

PCL_LS3D_INSTANTIATE_FlannKdTree(pcl::PointXYZ) PCL_LS3D_INSTANTIATE_FlannKdTree(pcl::PointXYZI)
    PCL_LS3D_INSTANTIATE_FlannKdTree(pcl::PointXYZRGB) PCL_LS3D_INSTANTIATE_FlannKdTree(pcl::PointNormal)
        PCL_LS3D_INSTANTIATE_FlannKdTree(pcl_ls3d::PointLiDAR)
