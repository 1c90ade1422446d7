#pragma once
/// \file las_header.h
/// \brief Private: what the LAS and the LAZ reader share (las_reader.cpp): the header with its
///        VLRs and EVLRs, and the conversion of point records into PointLiDAR in the local frame.
///        Both readers use these, so a LAZ file loads to exactly the cloud of its LAS twin.

#include <pcl_ls3d/io/cloud_io.h>

#include "las_format.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace las {

/// The header, VLRs and EVLRs checked against `size`. A compressed file passes with h.laz filled
/// from its LASzip VLR (checked against the point format); where its records lie is the LAZ
/// reader's to check. An uncompressed file's record block must fit in the file.
bool
parseHeader(const std::uint8_t* data, std::size_t size, LasHeaderInfo& h, std::string& error);

/// The LASzip VLR, or a COPC one (the info VLR, the hierarchy EVLR): records that describe how
/// the point data is compressed and laid out, and so belong to one encoding of it only.
bool
describesCompression(const LasVlr& v);

/// The header and VLRs of a file (parsed into `h`) rebuilt without the VLRs that describe its
/// compression (describesCompression): `extra_vlr` (a whole VLR's bytes, or empty) follows the
/// kept VLRs, then the bytes that lay between the VLRs and the points. The VLR count and offset
/// to the points are set, the format byte's compression bits cleared.
std::vector<std::uint8_t>
rebuildHead(const std::uint8_t* data, const LasHeaderInfo& h, const std::vector<std::uint8_t>& extra_vlr);

/// Appends the file's EVLRs (as they are, but for a COPC hierarchy, see describesCompression) to
/// `out`, a rebuilt file whose header is at its start, and sets the header's EVLR offset and
/// count.
void
appendEvlrs(const std::uint8_t* data, const LasHeaderInfo& h, std::vector<std::uint8_t>& out);

/// Sets the point counts of a rebuilt header `head` (of a file parsed into `h`): the total and
/// per return, legacy fields left zero where `h` left them zero (formats 6–10 in LAS 1.4).
void
writeCounts(std::vector<std::uint8_t>& head, const LasHeaderInfo& h, std::uint64_t n,
            const std::uint64_t by_return[15]);

/// Sets the header bounds of `head` from the records' integer bounds (zero when `empty`).
void
writeBounds(std::vector<std::uint8_t>& head, const LasHeaderInfo& h, const IntegerBox& box, bool empty);

/// The PointLiDAR fields a LAS record fills.
std::vector<std::string>
loadedFields(const LasHeaderInfo& h);

/// Every field of record `r` but x, y, z into `p`.
void
decodeAttributes(const std::uint8_t* r, const LasHeaderInfo& h, PointLiDAR& p);

/// \brief The local frame of a cloud: x_local = X · scale + shift, shift = offset − origin.
struct LocalFrame
{
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();

  float
  local(int k, std::int32_t q) const
  {
    return static_cast<float>(q * scale[k] + shift[k]);
  }
};

/// From the records' integer bounds: the file bounds in `info`, the origin (options' or the
/// auto-origin rule) and the frame; false when a coordinate is not finite or does not fit a float.
bool
chooseFrame(const IntegerBox& box, std::size_t n, const LasHeaderInfo& h, const LoadOptions& options,
            CloudInfo& info, LocalFrame& frame, std::string& error);

}  // namespace las

namespace laz_detail {

/// The records of a LAZ file (its header parsed by las::parseHeader) into `cloud`, decoded chunk
/// by chunk (laz/laz_reader.cpp).
bool
readLazPoints(const std::uint8_t* data, std::size_t size, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
              std::string& error, const LoadOptions& options);

/// Fills h.laz.chunk_count and chunk_table by opening the chunk table; false when the LAZ
/// container is unreadable.
bool
describeChunks(const std::uint8_t* data, std::size_t size, LasHeaderInfo& h, std::string& error);

/// Fills h.copc when the file is COPC (laz/copc_reader.h); false when its hierarchy is broken.
bool
describeCopc(const std::uint8_t* data, std::size_t size, LasHeaderInfo& h, std::string& error);

}  // namespace laz_detail
}  // namespace io
}  // namespace pcl_ls3d
