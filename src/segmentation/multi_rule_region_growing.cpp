/// \file multi_rule_region_growing.cpp
/// \brief Explicit instantiations of MultiRuleRegionGrowing for the common point types.
// pcl::search::KdTree<pcl_ls3d::PointLiDAR> needs PCL's template bodies.
#define PCL_NO_PRECOMPILE
#include <pcl_ls3d/point_types.h>
#include <pcl_ls3d/segmentation/impl/multi_rule_region_growing.hpp>
#include <pcl_ls3d/segmentation/multi_rule_region_growing.h>

PCL_LS3D_INSTANTIATE_MultiRuleRegionGrowing(pcl::PointXYZ)
    PCL_LS3D_INSTANTIATE_MultiRuleRegionGrowing(pcl::PointXYZI)
        PCL_LS3D_INSTANTIATE_MultiRuleRegionGrowing(pcl::PointXYZRGB)
            PCL_LS3D_INSTANTIATE_MultiRuleRegionGrowing(pcl::PointXYZRGBA)
                PCL_LS3D_INSTANTIATE_MultiRuleRegionGrowing(pcl_ls3d::PointLiDAR)
