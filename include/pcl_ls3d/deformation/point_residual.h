#pragma once
/// \file point_residual.h
/// \brief The point type of a deformation result cloud, one record per epoch point in the
///        epoch's order: x, y, z (the epoch point, local coordinates: file coordinates minus the
///        report's "local_origin", which the PCD header records too, io/pcd_io.h), residual and sigma (NaN when the point has no conjugate on
///        the reference), significant (0/1) and region (> 0 a region id of the report, −1 an
///        isolated detection below the minimum region size, 0 none). A plain PCL program reads
///        it with pcl::io::loadPCDFile<pcl_ls3d::PointResidual> (or any cloud type with these
///        field names).

#include <pcl/point_types.h>
#include <pcl/register_point_struct.h>

#include <cstdint>

namespace pcl_ls3d {

struct EIGEN_ALIGN16 PointResidual
{
  PCL_ADD_POINT4D;
  float residual = 0.f;  ///< signed distance along the rule's direction (LZD: z − z_reference)
  float sigma = 0.f;     ///< σ of the residual
  std::uint8_t significant = 0;
  std::int32_t region = 0;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

}  // namespace pcl_ls3d

POINT_CLOUD_REGISTER_POINT_STRUCT(pcl_ls3d::PointResidual,
                                  (float, x, x)(float, y, y)(float, z, z)(float, residual, residual)(
                                      float, sigma, sigma)(std::uint8_t, significant,
                                                           significant)(std::int32_t, region, region))
