/// \file las_reader.cpp
/// \brief LAS 1.0–1.4 reader: validates the header against the buffer size before touching a
///        point, then decodes the point block in one pass (see las_io.h).

#include <pcl_ls3d/io/las_io.h>

#include "las_format.h"
#include "las_header.h"
#include "las_region.h"
#include "laz/laszip_items.h"
#include "laz/laz_chunk_reader.h"
#include "local_origin.h"
#include "point_fields.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace pcl_ls3d {
namespace io {

const char* const kLazNotSupported =
    "compressed LAZ is not supported; decompress first, e.g. `las2las -i in.laz -o out.las` or "
    "`pdal translate in.laz out.las`";

const char* const kLaszipUserId = "laszip encoded";

std::uint16_t
lasPointRecordLength(int point_format)
{
  static const std::uint16_t kLength[11] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  return (point_format >= 0 && point_format <= 10) ? kLength[point_format] : 0;
}

namespace {

std::string
fixedString(const std::uint8_t* p, std::size_t n)
{
  std::size_t len = 0;
  while (len < n && p[len] != 0)
    ++len;
  return std::string(reinterpret_cast<const char*>(p), len);
}

template <typename... Args>
std::string
concat(const Args&... args)
{
  std::ostringstream s;
  (s << ... << args);
  return s.str();
}

/// Reads the VLRs between the header and the points; a VLR that would run past the point block is
/// an error (the file is inconsistent).
bool
readVlrs(const std::uint8_t* data, LasHeaderInfo& h, std::string& error)
{
  std::size_t pos = h.header_size;
  const std::size_t end = h.offset_to_points;
  h.vlrs.clear();
  for (std::uint32_t i = 0; i < h.number_of_vlrs; ++i) {
    if (pos + las::kVlrHeaderSize > end) {
      error = concat("VLR ", i + 1, " of ", h.number_of_vlrs, " starts at byte ", pos,
                     " but does not fit before the point data at byte ", end);
      return false;
    }
    const std::uint8_t* v = data + pos;
    LasVlr vlr;
    vlr.user_id = fixedString(v + 2, 16);
    vlr.record_id = las::get<std::uint16_t>(v + 18);
    const std::size_t length = las::get<std::uint16_t>(v + 20);
    vlr.description = fixedString(v + 22, 32);
    if (pos + las::kVlrHeaderSize + length > end) {
      error = concat("VLR ", i + 1, " (", detail::clip(vlr.user_id), "/", vlr.record_id, ") of ", length,
                     " bytes runs past the point data at byte ", end);
      return false;
    }
    vlr.data.assign(v + las::kVlrHeaderSize, v + las::kVlrHeaderSize + length);
    h.vlrs.push_back(std::move(vlr));
    pos += las::kVlrHeaderSize + length;
  }
  return true;
}

/// What can be said before the header is trusted at all: not empty, a LAS signature, at least
/// the 227 bytes every version's header has.
bool
checkSignature(const std::uint8_t* data, std::size_t size, std::string& error)
{
  if (size == 0) {
    error = "empty file";
    return false;
  }
  if (size < 4 || std::memcmp(data, "LASF", 4) != 0) {
    error = "not a LAS file (signature is not 'LASF')";
    return false;
  }
  if (size < las::kHeaderSize10) {
    error = concat("truncated LAS header: file has ", size, " bytes, a header needs at least 227");
    return false;
  }
  return true;
}

/// Version 1.0-1.4 and a header size field at least what the version requires and within the file.
bool
readVersion(const std::uint8_t* data, std::size_t size, LasHeaderInfo& h, std::string& error)
{
  h.version_major = data[las::kVersionMajor];
  h.version_minor = data[las::kVersionMinor];
  if (h.version_major != 1 || h.version_minor > 4) {
    error = concat("unsupported LAS version ", int(h.version_major), ".", int(h.version_minor),
                   " (1.0-1.4 supported)");
    return false;
  }
  h.header_size = las::get<std::uint16_t>(data + las::kHeaderSize);
  const std::size_t required = las::headerSizeFor(h.version_minor);
  if (h.header_size < required) {
    error = concat("LAS 1.", int(h.version_minor), " header size field is ", h.header_size,
                   ", smaller than the ", required, " bytes the version requires");
    return false;
  }
  if (size < h.header_size) {
    error = concat("truncated LAS header: file has ", size, " bytes, header size is ", h.header_size);
    return false;
  }
  return true;
}

/// Point format 0-10 and a record length that holds the format (the rest of each record is extra
/// bytes). The compression bits are noted.
bool
readPointFormat(const std::uint8_t* data, LasHeaderInfo& h, std::string& error)
{
  const std::uint8_t format_byte = data[las::kPointFormat];
  h.laz.compressed = (format_byte & 0xC0) != 0;  // LASzip sets bit 7 (and bit 6 in some writers)
  h.point_format = format_byte & 0x3F;
  const std::uint16_t min_length = lasPointRecordLength(h.point_format);
  if (min_length == 0) {
    error = concat("unsupported LAS point format ", int(h.point_format), " (0-10 supported)");
    return false;
  }
  h.record_length = las::get<std::uint16_t>(data + las::kRecordLength);
  if (h.record_length < min_length) {
    error = concat("point record length ", h.record_length, " is smaller than the ", min_length,
                   " bytes point format ", int(h.point_format), " needs");
    return false;
  }
  h.extra_bytes_per_record = static_cast<std::uint16_t>(h.record_length - min_length);
  return true;
}

/// The fields every version has, checked only where a coordinate depends on them: a scale of
/// zero or a non-finite scale or offset would make every point meaningless.
bool
readLegacyFields(const std::uint8_t* data, LasHeaderInfo& h, std::string& error)
{
  h.file_source_id = las::get<std::uint16_t>(data + las::kFileSourceId);
  h.global_encoding = las::get<std::uint16_t>(data + las::kGlobalEncoding);
  h.system_identifier = fixedString(data + las::kSystemId, 32);
  h.generating_software = fixedString(data + las::kSoftware, 32);
  h.offset_to_points = las::get<std::uint32_t>(data + las::kOffsetToPoints);
  h.number_of_vlrs = las::get<std::uint32_t>(data + las::kNumberOfVlrs);
  h.legacy_point_count = las::get<std::uint32_t>(data + las::kLegacyCount);
  for (int r = 0; r < 5; ++r)
    h.points_by_return[r] = las::get<std::uint32_t>(data + las::kLegacyByReturn + 4 * r);
  for (int k = 0; k < 3; ++k) {
    h.scale[k] = las::get<double>(data + las::kScale + 8 * k);
    h.offset[k] = las::get<double>(data + las::kOffset + 8 * k);
    h.max[k] = las::get<double>(data + las::kMaxX + 16 * k);
    h.min[k] = las::get<double>(data + las::kMaxX + 16 * k + 8);
    if (!std::isfinite(h.scale[k]) || h.scale[k] == 0.0 || !std::isfinite(h.offset[k])) {
      error = concat("invalid scale factor or offset for ", "xyz"[k], " (scale ", h.scale[k], ", offset ",
                     h.offset[k], ")");
      return false;
    }
  }
  return true;
}

/// The point count: the legacy 32-bit one, or from 1.4 the 64-bit one when set (then with 15
/// returns); both set and different is an error.
bool
readPointCount(const std::uint8_t* data, LasHeaderInfo& h, std::string& error)
{
  h.point_count = h.legacy_point_count;
  if (h.version_minor < 4)
    return true;
  const std::uint64_t count64 = las::get<std::uint64_t>(data + las::kCount64);
  if (count64 != 0 && h.legacy_point_count != 0 && count64 != h.legacy_point_count) {
    error = concat("point count mismatch: legacy count ", h.legacy_point_count, " vs 64-bit count ", count64);
    return false;
  }
  if (count64 != 0) {
    h.point_count = count64;
    for (int r = 0; r < 15; ++r)
      h.points_by_return[r] = las::get<std::uint64_t>(data + las::kByReturn64 + 8 * r);
  }
  return true;
}

/// The point data starts after the header and within the file (the VLRs lie in between).
bool
checkPointOffset(const LasHeaderInfo& h, std::size_t size, std::string& error)
{
  if (h.offset_to_points < h.header_size) {
    error = concat("offset to point data (", h.offset_to_points, ") lies inside the ", h.header_size,
                   "-byte header");
    return false;
  }
  if (h.offset_to_points > size) {
    error = concat("offset to point data (", h.offset_to_points, ") is beyond the end of the file (", size,
                   " bytes)");
    return false;
  }
  return true;
}

/// The point block must fit; later EVLRs / waveform data may follow it, so more bytes are fine.
bool
checkPointBlock(const LasHeaderInfo& h, std::size_t size, std::string& error)
{
  const std::uint64_t available = size - h.offset_to_points;
  if (h.point_count > available / h.record_length) {
    error = concat("point block truncated or point count wrong: header says ", h.point_count, " points of ",
                   h.record_length, " bytes from byte ", h.offset_to_points, " but only ", available,
                   " bytes follow (room for ", available / h.record_length, " points)");
    return false;
  }
  return true;
}

/// The LASzip VLR of a compressed file, checked against the point format and record length; a
/// LASzip VLR also marks a file compressed whose format byte does not say so.
bool
readLaszipVlr(LasHeaderInfo& h, std::string& error)
{
  const LasVlr* found = nullptr;
  for (const LasVlr& v : h.vlrs)
    if (v.user_id == kLaszipUserId && v.record_id == 22204)
      found = &v;
  if (!found && !h.laz.compressed)
    return true;
  h.laz.compressed = true;
  if (!found) {
    error = "the point format byte marks the records as compressed (LAZ), but the file has no "
            "LASzip VLR to say how";
    return false;
  }
  laz::LaszipVlr vlr;
  if (!laz::parseLaszipVlr(found->data.data(), found->data.size(), h.point_format, h.record_length, vlr,
                           error))
    return false;
  h.laz.compressor = static_cast<int>(vlr.compressor);
  h.laz.chunk_size = vlr.chunk_size;
  h.laz.items = laz::describeItems(vlr);
  return true;
}

/// LAS 1.4 EVLRs: each must lie after the point data's start and within the file.
bool
readEvlrs(const std::uint8_t* data, std::size_t size, LasHeaderInfo& h, std::string& error)
{
  h.evlrs.clear();
  if (h.version_minor < 4)
    return true;
  std::uint64_t pos = las::get<std::uint64_t>(data + las::kEvlrStart);
  const std::uint32_t count = las::get<std::uint32_t>(data + las::kEvlrCount);
  if (count > 0 && pos < h.offset_to_points) {
    error = concat("the EVLRs start at byte ", pos, ", before the point data at byte ", h.offset_to_points);
    return false;
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    if (pos > size || size - pos < las::kEvlrHeaderSize) {
      error = concat("EVLR ", i + 1, " of ", count, " at byte ", pos, " runs past the end of the file (",
                     size, " bytes)");
      return false;
    }
    const std::uint8_t* v = data + pos;
    const std::uint64_t length = las::get<std::uint64_t>(v + 20);
    if (length > size - pos - las::kEvlrHeaderSize) {
      error = concat("EVLR ", i + 1, " of ", count, " at byte ", pos, " holds ", length,
                     " bytes, past the end of the file (", size, " bytes)");
      return false;
    }
    LasVlr vlr;
    vlr.user_id = fixedString(v + 2, 16);
    vlr.record_id = las::get<std::uint16_t>(v + 18);
    vlr.description = fixedString(v + 28, 32);
    vlr.data.assign(v + las::kEvlrHeaderSize, v + las::kEvlrHeaderSize + length);
    h.evlrs.push_back(std::move(vlr));
    pos += las::kEvlrHeaderSize + length;
  }
  return true;
}

}  // namespace

namespace las {

bool
parseHeader(const std::uint8_t* data, std::size_t size, LasHeaderInfo& h, std::string& error)
{
  // `h` is left as it was for a file that is no LAS header at all; later stages fill it in order,
  // so a failing check leaves what was read up to it.
  if (!checkSignature(data, size, error))
    return false;
  h = LasHeaderInfo();
  if (!(readVersion(data, size, h, error) && readPointFormat(data, h, error) &&
        readLegacyFields(data, h, error) && readPointCount(data, h, error) &&
        checkPointOffset(h, size, error) && readVlrs(data, h, error) && readLaszipVlr(h, error)))
    return false;
  if (!h.laz.compressed && !checkPointBlock(h, size, error))
    return false;
  return readEvlrs(data, size, h, error);
}

bool
describesCompression(const LasVlr& v)
{
  return (v.user_id == kLaszipUserId && v.record_id == 22204) || v.user_id == "copc";
}

std::vector<std::uint8_t>
rebuildHead(const std::uint8_t* data, const LasHeaderInfo& h, const std::vector<std::uint8_t>& extra_vlr)
{
  std::vector<std::uint8_t> head(data, data + h.header_size);
  std::size_t pos = h.header_size;
  std::uint32_t count = 0;
  for (const LasVlr& v : h.vlrs) {
    const std::size_t bytes = kVlrHeaderSize + v.data.size();
    if (!describesCompression(v)) {
      head.insert(head.end(), data + pos, data + pos + bytes);
      ++count;
    }
    pos += bytes;
  }
  head.insert(head.end(), extra_vlr.begin(), extra_vlr.end());
  count += extra_vlr.empty() ? 0 : 1;
  head.insert(head.end(), data + pos, data + h.offset_to_points);
  head[kPointFormat] = h.point_format;
  put<std::uint32_t>(head.data() + kNumberOfVlrs, count);
  put<std::uint32_t>(head.data() + kOffsetToPoints, static_cast<std::uint32_t>(head.size()));
  return head;
}

void
appendEvlrs(const std::uint8_t* data, const LasHeaderInfo& h, std::vector<std::uint8_t>& out)
{
  std::uint64_t pos = h.evlrs.empty() ? 0 : get<std::uint64_t>(data + kEvlrStart);
  std::uint32_t kept = 0;
  const std::size_t start = out.size();
  for (const LasVlr& v : h.evlrs) {
    const std::uint64_t bytes = kEvlrHeaderSize + v.data.size();
    if (!describesCompression(v)) {
      out.insert(out.end(), data + pos, data + pos + bytes);
      ++kept;
    }
    pos += bytes;
  }
  if (h.evlrs.empty())
    return;
  put<std::uint64_t>(out.data() + kEvlrStart, kept ? start : 0);
  put<std::uint32_t>(out.data() + kEvlrCount, kept);
}

void
writeCounts(std::vector<std::uint8_t>& head, const LasHeaderInfo& h, std::uint64_t n,
            const std::uint64_t by_return[15])
{
  // Legacy fields stay zero where the input left them zero (formats 6–10 in LAS 1.4).
  const bool legacy = h.legacy_point_count != 0 || h.version_minor < 4;
  const auto clip = [](std::uint64_t v) {
    return static_cast<std::uint32_t>(std::min<std::uint64_t>(v, 0xFFFFFFFFu));
  };
  put<std::uint32_t>(head.data() + kLegacyCount, legacy ? clip(n) : 0u);
  for (int r = 0; r < 5; ++r)
    put<std::uint32_t>(head.data() + kLegacyByReturn + 4 * r, legacy ? clip(by_return[r]) : 0u);
  if (h.version_minor >= 4 && head.size() >= kHeaderSize14) {
    put<std::uint64_t>(head.data() + kCount64, n);
    for (int r = 0; r < 15; ++r)
      put<std::uint64_t>(head.data() + kByReturn64 + 8 * r, by_return[r]);
  }
}

void
writeBounds(std::vector<std::uint8_t>& head, const LasHeaderInfo& h, const IntegerBox& box, bool empty)
{
  for (int c = 0; c < 3; ++c) {
    double a = 0.0, b = 0.0;
    if (!empty) {
      a = box.lo[c] * h.scale[c] + h.offset[c];
      b = box.hi[c] * h.scale[c] + h.offset[c];
    }
    put<double>(head.data() + kMaxX + 16 * c, std::max(a, b));
    put<double>(head.data() + kMaxX + 16 * c + 8, std::min(a, b));
  }
}

std::vector<std::string>
loadedFields(const LasHeaderInfo& h)
{
  std::vector<std::string> fields = {
      "x", "y", "z", "intensity", "return_number", "number_of_returns", "classification", "point_source_id"};
  if (las::gpsTimeOffset(h.point_format))
    fields.push_back("gps_time");
  return fields;
}

void
decodeAttributes(const std::uint8_t* r, const LasHeaderInfo& h, PointLiDAR& p)
{
  p.intensity = static_cast<float>(las::get<std::uint16_t>(r + 12));
  const std::uint8_t returns = r[14];
  if (h.point_format >= 6) {
    p.return_number = returns & 0x0F;
    p.number_of_returns = returns >> 4;
    p.classification = r[16];
    p.point_source_id = las::get<std::uint16_t>(r + 20);
  } else {
    p.return_number = returns & 0x07;
    p.number_of_returns = (returns >> 3) & 0x07;
    p.classification = r[15] & 0x1F;
    p.point_source_id = las::get<std::uint16_t>(r + 18);
  }
  const std::size_t gps_offset = las::gpsTimeOffset(h.point_format);
  p.gps_time = gps_offset ? las::get<double>(r + gps_offset) : 0.0;
}

bool
chooseFrame(const IntegerBox& box, std::size_t n, const LasHeaderInfo& h, const LoadOptions& options,
            CloudInfo& info, LocalFrame& frame, std::string& error)
{
  // The file coordinates' bounds from the integer bounds (a negative scale swaps the ends).
  for (int k = 0; k < 3 && n > 0; ++k) {
    const double a = box.lo[k] * h.scale[k] + h.offset[k], b = box.hi[k] * h.scale[k] + h.offset[k];
    info.min_file[k] = std::min(a, b);
    info.max_file[k] = std::max(a, b);
  }
  if (n > 0 && (!info.min_file.allFinite() || !info.max_file.allFinite())) {
    error = "scale and offset give non-finite coordinates";
    return false;
  }
  info.origin = options.use_origin ? options.origin : chooseOrigin(info.min_file, info.max_file);
  frame.scale = h.scale;
  frame.shift = h.offset - info.origin;
  // The local coordinates' extremes (at the integer bounds) must fit in a float.
  Eigen::Vector3d local_lo, local_hi;
  for (int k = 0; k < 3; ++k) {
    local_lo[k] = box.lo[k] * h.scale[k] + frame.shift[k];
    local_hi[k] = box.hi[k] * h.scale[k] + frame.shift[k];
  }
  return n == 0 || detail::fitsInFloat(local_lo, local_hi, Eigen::Vector3d::Zero(), error);
}

}  // namespace las

bool
readLasHeader(const std::uint8_t* data, std::size_t size, LasHeaderInfo& h, std::string& error)
{
  return las::parseHeader(data, size, h, error) &&
         (!h.laz.compressed || (laz_detail::describeChunks(data, size, h, error) &&
                                laz_detail::describeCopc(data, size, h, error)));
}

namespace {

/// A box query: the records inside become a LAS file of their own (las_region.h), read as any
/// other; `info` describes the whole input (its header, compression and octree) and what the
/// query read and left out.
bool
readLasRegion(const std::uint8_t* data, std::size_t size, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
              std::string& error, const LoadOptions& options)
{
  LasHeaderInfo& h = info.las;
  std::vector<std::uint8_t> las;
  RegionInfo read;
  if ((h.laz.compressed && !(laz_detail::describeChunks(data, size, h, error) &&
                             laz_detail::describeCopc(data, size, h, error))) ||
      !las::extractRegion(data, size, h, *options.region, las, read, error))
    return false;
  LoadOptions inner = options;
  inner.region.reset();
  inner.allow_empty = true;
  CloudInfo part;
  if (!readLas(las.data(), las.size(), cloud, part, error, inner))
    return false;
  info.origin = part.origin;
  info.min_file = part.min_file;
  info.max_file = part.max_file;
  info.points_in_file = static_cast<std::size_t>(h.point_count);
  info.points_loaded = part.points_loaded;
  info.points_outside_region = info.points_in_file - info.points_loaded;
  info.region = read;
  if (cloud.empty() && !options.allow_empty) {
    error = "no point of the file lies inside the region";
    return false;
  }
  return true;
}

}  // namespace

bool
readLas(const std::uint8_t* data, std::size_t size, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info,
        std::string& error, const LoadOptions& options)
{
  info = CloudInfo();
  info.format = "las";
  cloud.clear();
  if (!las::parseHeader(data, size, info.las, error))
    return false;
  const LasHeaderInfo& h = info.las;
  info.fields = las::loadedFields(h);
  if (options.region)
    return readLasRegion(data, size, cloud, info, error, options);
  if (h.laz.compressed) {
    if (!laz_detail::readLazPoints(data, size, cloud, info, error, options) ||
        !laz_detail::describeCopc(data, size, info.las, error))
      return false;
  } else {
    const std::size_t n = static_cast<std::size_t>(h.point_count);
    const std::uint8_t* block = data + h.offset_to_points;
    info.points_in_file = n;
    las::IntegerBox box;
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k)
        box.add(k, las::get<std::int32_t>(block + i * h.record_length + 4 * k));
    las::LocalFrame frame;
    if (!las::chooseFrame(box, n, h, options, info, frame, error))
      return false;
    cloud.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint8_t* r = block + i * h.record_length;
      PointLiDAR& p = cloud[i];
      p.x = frame.local(0, las::get<std::int32_t>(r));
      p.y = frame.local(1, las::get<std::int32_t>(r + 4));
      p.z = frame.local(2, las::get<std::int32_t>(r + 8));
      las::decodeAttributes(r, h, p);
    }
    info.points_loaded = n;
  }
  cloud.width = static_cast<std::uint32_t>(cloud.size());
  cloud.height = 1;
  cloud.is_dense = true;
  if (cloud.empty() && !options.allow_empty) {
    error = h.laz.compressed ? "the LAZ file holds no points" : "the LAS file holds no points";
    return false;
  }
  return true;
}

}  // namespace io
}  // namespace pcl_ls3d
