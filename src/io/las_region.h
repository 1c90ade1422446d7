#pragma once
/// \file las_region.h
/// \brief Private: a box query on a LAS, LAZ or COPC file in memory. The records inside the box
///        become a LAS file of their own (header, VLRs and EVLRs of the input, counts and bounds
///        of the records kept), which readLas() and LasRecordFile then read as any other. A COPC
///        file decodes only the octree nodes the box meets; LAS and LAZ are read through, chunk
///        by chunk, keeping only the records inside.

#include <pcl_ls3d/io/cloud_io.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace las {

/// Is the region usable: a finite, non-inverted box (z too when used) and a level the file can
/// honour? False with a one-line reason.
bool
checkRegion(const Region& region, std::string& error);

/// Does a record's X, Y, Z (file coordinates, in double) lie inside the region's box?
bool
insideRegion(const std::uint8_t* record, const LasHeaderInfo& h, const Region& region);

/// The records of the file [data, data + size) (header parsed into `h`) inside `region`, as an
/// uncompressed LAS file in `las`. `read` says what was decoded. False with a one-line reason.
bool
extractRegion(const std::uint8_t* data, std::size_t size, const LasHeaderInfo& h, const Region& region,
              std::vector<std::uint8_t>& las, RegionInfo& read, std::string& error);

}  // namespace las
}  // namespace io
}  // namespace pcl_ls3d
