#pragma once
/// \file las_io.h
/// \brief LAS 1.0–1.4 reader and writer (point formats 0–10), and LAZ, its LASzip-compressed
///        form, on memory buffers so the same code serves files, tests and the fuzzer.
///
/// Kept fields: X, Y, Z (via scale/offset, in double), intensity, return number, number of
/// returns, classification (low 5 bits of byte 15 in formats 0–5, byte 16 in 6–10), point-source
/// id (offset 18 / 20), GPS time (formats 1, 3–10). Extra bytes beyond a format's minimum record
/// length are skipped. Everything else in a record (scan angle, flags, RGB, NIR, waveform packets)
/// is not kept and is written as zero.
///
/// LAZ (point-format bit 0x80/0x40 or a LASzip VLR) is read by the same functions: readLas()
/// decodes the records chunk by chunk (in parallel with OpenMP when the file has a chunk table)
/// straight into the cloud, which is exactly the cloud of the file's LAS twin; CloudInfo::format
/// stays "las" and LasHeaderInfo::laz says how the file is compressed. Decoded: compressors 1
/// (pointwise), 2 (pointwise-chunked) with items POINT10, GPSTIME11, RGB12, BYTE versions 1–2, and
/// 3 (layered-chunked, formats 6–10) through the layered item coders; fixed and variable chunk
/// sizes; a missing or unusable chunk table (fixed-size chunks are then found by decoding them in
/// order). Written: point formats 0–3 pointwise-chunked and 6–8 layered-chunked (items version 2
/// resp. 3), 50 000 points per chunk, with a chunk table, the LASzip VLR last and bit 0x80 set, so
/// any LASzip reader opens the file. Waveform formats (4, 5, 9, 10) are refused with one line.
/// COPC (`.copc.laz`) is LAZ whose variable-size chunks are the nodes of an octree: read whole
/// as any LAZ file (LasHeaderInfo::copc then describes the octree), or through a box query
/// (LoadOptions::region, cloud_io.h), which decodes only the nodes the box meets.
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

/// The one-line message for compressed input (kept for the tools' older messages; LAZ is read now).
extern const char* const kLazNotSupported;

/// Parses only the public header, VLRs and EVLRs of an in-memory LAS or LAZ file and validates
/// them against `size` (no point is decoded; for LAZ the chunk table is read to fill
/// header.laz). Returns false with a one-line reason.
bool
readLasHeader(const std::uint8_t* data, std::size_t size, LasHeaderInfo& header, std::string& error);

/// Parses a whole in-memory LAS file into local coordinates (see cloud_io.h for the origin rule
/// and the handling of empty results). Never reads outside [data, data + size).
bool
readLas(const std::uint8_t* data, std::size_t size, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
        std::string& error, const LoadOptions& options = {});

/// Reads a LAS file: maps it read-only (or bulk-reads it when mmap fails), then readLas().
bool
readLasFile(const std::string& path, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info, std::string& error,
            const LoadOptions& options = {});

/// Encodes a cloud as a LAS file in memory (header, options.las_vlrs, point records).
bool
writeLas(const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
         std::vector<std::uint8_t>& out, std::string& error, const SaveOptions& options = {});

/// Writes a LAS file (no overwrite check here; saveCloud() does it).
bool
writeLasFile(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
             std::string& error, const SaveOptions& options = {});

/// Encodes a cloud as a LAZ file in memory: writeLas(), then compressLas().
bool
writeLaz(const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
         std::vector<std::uint8_t>& out, std::string& error, const SaveOptions& options = {});

/// Writes a LAZ file (no overwrite check here; saveCloud() does it).
bool
writeLazFile(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
             std::string& error, const SaveOptions& options = {});

/// Compresses an in-memory LAS file into LAZ, losslessly: every record byte, the header, the VLRs
/// (a LASzip VLR is added last, the format byte gets bit 0x80) and the EVLRs are kept; only the
/// offsets that move with them change. COPC's info VLR and hierarchy EVLR, which would describe
/// chunks this file does not have, are left out. `chunk_size` points per chunk. Waveform formats (4, 5, 9,
/// 10) are refused.
bool
compressLas(const std::uint8_t* las, std::size_t size, std::vector<std::uint8_t>& laz, std::string& error,
            std::uint32_t chunk_size = 50000);

/// Decompresses an in-memory LAZ file into LAS: the records decoded, the LASzip VLR removed and
/// the compression bits cleared; the header, the other VLRs and the EVLRs are kept (a COPC
/// file's info VLR and hierarchy EVLR are removed too: they locate compressed chunks).
bool
decompressLaz(const std::uint8_t* laz, std::size_t size, std::vector<std::uint8_t>& las, std::string& error);

}  // namespace io
}  // namespace pcl_ls3d
