#pragma once
/// \file pcd_io.h
/// \brief PCD reader (v0.5–0.7; DATA ascii, binary, binary_compressed) on a memory buffer, so the
///        same code serves files, tests and the fuzzer. Writing goes through PCL's PCDWriter
///        (saveCloud in cloud_io.h).
///
/// The header is checked before anything is allocated: FIELDS, SIZE, TYPE (F 4/8, U and I
/// 1/2/4/8) and COUNT (optional, >= 1) must agree; WIDTH x HEIGHT must equal POINTS; counts are
/// plain decimal integers. Then the header's claim is checked against the bytes present: binary
/// needs POINTS x record size bytes; binary_compressed needs its compressed block and an
/// uncompressed size equal to POINTS x record size (and no more than LZF can expand); ASCII needs
/// at least two bytes per value. A file that claims a billion points but holds ten fails there,
/// with one line saying so, before any allocation. Fields mapped: see cloud_io.h / pcl_formats.h.

#include <pcl_ls3d/io/cloud_io.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace pcl_ls3d {
namespace io {

/// Parses an in-memory PCD file into local coordinates (cloud_io.h describes the origin rule).
/// Never reads outside [data, data + size); returns false with a one-line reason.
bool
readPcd(const std::uint8_t* data, std::size_t size, pcl::PointCloud<PointLiDAR>& cloud,
        CloudInfo& info, std::string& error, const LoadOptions& options = {});

}  // namespace io
}  // namespace pcl_ls3d
