#pragma once
/// \file las_io.h
/// \brief LAS 1.0–1.4 reader and writer (uncompressed, point formats 0–10), on memory buffers so
///        the same code serves files, tests and the fuzzer.
///
/// Kept fields: X, Y, Z (via scale/offset, in double), intensity, return number, number of
/// returns, classification (low 5 bits of byte 15 in formats 0–5, byte 16 in 6–10), point-source
/// id (offset 18 / 20), GPS time (formats 1, 3–10). Extra bytes beyond a format's minimum record
/// length are skipped. Everything else in a record (scan angle, flags, RGB, NIR, waveform packets)
/// is not kept and is written as zero. LAZ is detected (point-format bits 0x80/0x40 or the LASzip
/// VLR) and refused with a hint.
///
/// The reader is lenient about version/format pairs (any of formats 0–10 in any 1.0–1.4 file) but
/// strict about sizes: every offset and count is checked against the buffer before use, so a bad
/// file costs at most one allocation proportional to its real size. EVLRs (LAS 1.4) and waveform
/// packets are ignored. The writer is strict: formats 2–3 need 1.2+, 4–5 need 1.3+, 6–10 need 1.4;
/// classes > 31 or returns > 7 need formats 6–10 (refused, never truncated); intensity is rounded
/// and clamped to 0–65535. It writes header sizes 227/235/375, offset to points = header + VLRs,
/// bounds from the quantised values, legacy and (1.4) 64-bit counts and per-return counts (legacy
/// fields zero for formats 6–10, as 1.4 requires), the WKT bit for formats 6–10, and bit 0 only on
/// request (SaveOptions::las_adjusted_standard_gps_time). The VLRs in SaveOptions are written as
/// given (except an extra-bytes or LASzip VLR, which would misdescribe the records): a GeoTIFF CRS
/// copied from a 1.2 file into a 1.4 format-6 file stays GeoTIFF.

#include <pcl_ls3d/io/cloud_io.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {

/// Minimum record length of LAS point format 0–10 (20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67);
/// 0 for an unknown format.
std::uint16_t
lasPointRecordLength(int point_format);

/// The one-line message for compressed input.
extern const char* const kLazNotSupported;

/// Parses only the public header and VLRs of an in-memory LAS file and validates them against
/// `size` (no point is read). Returns false with a one-line reason.
bool
readLasHeader(const std::uint8_t* data, std::size_t size, LasHeaderInfo& header,
              std::string& error);

/// Parses a whole in-memory LAS file into local coordinates (see cloud_io.h for the origin rule
/// and the handling of empty results). Never reads outside [data, data + size).
bool
readLas(const std::uint8_t* data, std::size_t size, pcl::PointCloud<PointLiDAR>& cloud,
        CloudInfo& info, std::string& error, const LoadOptions& options = {});

/// Reads a LAS file: maps it read-only (or bulk-reads it when mmap fails), then readLas().
bool
readLasFile(const std::string& path, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
            std::string& error, const LoadOptions& options = {});

/// Encodes a cloud as a LAS file in memory (header, options.las_vlrs, point records).
bool
writeLas(const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
         std::vector<std::uint8_t>& out, std::string& error, const SaveOptions& options = {});

/// Writes a LAS file (no overwrite check here; saveCloud() does it).
bool
writeLasFile(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud,
             const Eigen::Vector3d& origin, std::string& error, const SaveOptions& options = {});

}  // namespace io
}  // namespace pcl_ls3d
