// Explicit instantiations of SampleConsensusModelSurfaceMatching, and of PCL's sample-consensus
// estimators for pcl_ls3d::PointLiDAR (not one of PCL's precompiled types), so that
// pcl::LeastMedianSquares<PointLiDAR> & co. link without PCL_NO_PRECOMPILE in user code.
#define PCL_NO_PRECOMPILE
#include <pcl_ls3d/point_types.h>
#include <pcl_ls3d/sample_consensus/impl/sac_model_surface_matching.hpp>

#include <pcl/point_types.h>
#include <pcl/sample_consensus/impl/lmeds.hpp>
#include <pcl/sample_consensus/impl/msac.hpp>
#include <pcl/sample_consensus/impl/ransac.hpp>

PCL_LS3D_INSTANTIATE_SampleConsensusModelSurfaceMatching(pcl::PointXYZ)
    PCL_LS3D_INSTANTIATE_SampleConsensusModelSurfaceMatching(pcl::PointXYZI)
        PCL_LS3D_INSTANTIATE_SampleConsensusModelSurfaceMatching(pcl::PointNormal)
            PCL_LS3D_INSTANTIATE_SampleConsensusModelSurfaceMatching(pcl_ls3d::PointLiDAR)

                template class PCL_EXPORTS pcl::LeastMedianSquares<pcl_ls3d::PointLiDAR>;
template class PCL_EXPORTS pcl::RandomSampleConsensus<pcl_ls3d::PointLiDAR>;
template class PCL_EXPORTS pcl::MEstimatorSampleConsensus<pcl_ls3d::PointLiDAR>;
