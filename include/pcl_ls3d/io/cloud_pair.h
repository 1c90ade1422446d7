#pragma once
/// \file cloud_pair.h
/// \brief Two clouds that are matched against each other (register, compare, deformation), loaded
///        the one way every pair tool loads them: the target first, the source around the
///        target's local origin, both CRSs checked, and heights in another unit than the plan
///        converted to it (working coordinates, common/height_units.h).
///
/// CRS policy of a pair: an input in degrees or earth-centred is refused (distances and heights
/// in degrees give a wrong answer that still converges); inputs that declare different horizontal
/// CRSs are noted as warnings and used as they are; a file that declares no CRS (a PCD or XYZ
/// exported from the other, an old PLY) is taken in the units of the fallback CRS when one is
/// given, else of its partner.

#include <pcl_ls3d/common/height_units.h>
#include <pcl_ls3d/io/cloud_io.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {

/// \brief A loaded pair in working coordinates around working_origin.
struct CloudPair
{
  pcl::PointCloud<PointLiDAR>::Ptr target{new pcl::PointCloud<PointLiDAR>};
  pcl::PointCloud<PointLiDAR>::Ptr source{new pcl::PointCloud<PointLiDAR>};
  CloudInfo target_info, source_info;  ///< target_info.origin is the files' local origin
  HeightUnits heights;                 ///< plan units per height unit of each file
  Eigen::Vector3d working_origin = Eigen::Vector3d::Zero();
  std::vector<std::string> warnings;  ///< different horizontal CRSs (the pair is used as it is)
  std::vector<std::string> notes;     ///< one line per file whose heights were converted
};

/// \brief Loads \a target_path, then \a source_path around the target's origin, checks their CRSs
///        and converts the heights (see the file comment). False with one line in \a error when a
///        file cannot be loaded or is not in lengths.
/// \param[in] fallback_wkt CRS of a file that declares none (empty: its partner's)
bool
loadCloudPair(const std::string& target_path, const std::string& source_path, CloudPair& pair,
              std::string& error, const std::string& fallback_wkt = "");

}  // namespace io
}  // namespace pcl_ls3d
