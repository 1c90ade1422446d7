#pragma once
/// \file point_types.h
/// \brief The point type the readers fill: PCL's x, y, z plus the LAS fields that carry meaning
///        for strip adjustment and segmentation (classification, flight strip, time, returns).

#include <pcl/point_types.h>
#include <pcl/register_point_struct.h>

#include <cstdint>

namespace pcl_ls3d {

/// \brief A LiDAR return in local coordinates (see io::LocalOrigin): float x, y, z as every PCL
///        algorithm expects, and the per-point LAS attributes kept by the readers and writers.
struct EIGEN_ALIGN16 PointLiDAR
{
  PCL_ADD_POINT4D;
  float intensity = 0.f;
  double gps_time = 0.0;              ///< GPS time [s]; 0 where the format has none
  std::uint16_t point_source_id = 0;  ///< flight-strip id (LAS PointSourceId)
  std::uint8_t classification = 0;    ///< ASPRS class code (2 ground, 6 building, ...)
  std::uint8_t return_number = 1;
  std::uint8_t number_of_returns = 1;

  inline PointLiDAR()
  {
    x = y = z = 0.f;
    data[3] = 1.f;
  }
  inline PointLiDAR(float px, float py, float pz)
  {
    x = px;
    y = py;
    z = pz;
    data[3] = 1.f;
  }
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

}  // namespace pcl_ls3d

POINT_CLOUD_REGISTER_POINT_STRUCT(
    pcl_ls3d::PointLiDAR,
    (float, x, x)(float, y, y)(float, z, z)(float, intensity, intensity)(double, gps_time, gps_time)(
        std::uint16_t, point_source_id, point_source_id)(std::uint8_t, classification, classification)(
        std::uint8_t, return_number, return_number)(std::uint8_t, number_of_returns, number_of_returns))
