/// \file las_writer.cpp
/// \brief LAS 1.0–1.4 writer (formats 0–10): header per the ASPRS specification, bounds and
///        return counts computed from the quantised records, VLRs passed through.

#include <pcl_ls3d/io/las_io.h>

#include "las_format.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>
#include <sstream>

namespace pcl_ls3d {
namespace io {

namespace {

void
putString(std::uint8_t* p, const std::string& s, std::size_t n)
{
  std::memcpy(p, s.data(), std::min(n, s.size()));
}

/// Smallest LAS 1.x minor version that defines a point format.
int
minimumMinorFor(int format)
{
  return format <= 1 ? 0 : (format <= 3 ? 2 : (format <= 5 ? 3 : 4));
}

bool
checkOptions(const pcl::PointCloud<PointLiDAR>& cloud, const SaveOptions& o, std::string& error)
{
  const int format = o.las_point_format, minor = o.las_minor_version;
  if (format > 10) {
    error = "LAS point format " + std::to_string(format) + " does not exist (0-10)";
    return false;
  }
  if (minor > 4) {
    error = "LAS version 1." + std::to_string(minor) + " is not supported (1.0-1.4)";
    return false;
  }
  if (minor < minimumMinorFor(format)) {
    error = "LAS point format " + std::to_string(format) + " needs LAS 1." +
            std::to_string(minimumMinorFor(format)) + " or later";
    return false;
  }
  if (!o.las_scale.allFinite() || (o.las_scale.array() <= 0.0).any()) {
    error = "LAS scale must be positive";
    return false;
  }
  if (minor < 4 && cloud.size() > std::numeric_limits<std::uint32_t>::max()) {
    error = "more than 2^32-1 points need LAS 1.4";
    return false;
  }
  // Formats 0-5 hold 5-bit classes and 3-bit return numbers; refuse rather than truncate.
  const unsigned max_class = format >= 6 ? 255 : 31, max_return = format >= 6 ? 15 : 7;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const PointLiDAR& p = cloud[i];
    if (p.classification > max_class) {
      error = "point " + std::to_string(i) + " has class " + std::to_string(p.classification) +
              ", which LAS point format " + std::to_string(format) +
              " cannot store (max 31); use format 6-10 (LAS 1.4)";
      return false;
    }
    if (p.return_number > max_return || p.number_of_returns > max_return) {
      error = "point " + std::to_string(i) + " has return " + std::to_string(p.return_number) + "/" +
              std::to_string(p.number_of_returns) + ", beyond the " + std::to_string(max_return) +
              " that LAS point format " + std::to_string(format) + " can store";
      return false;
    }
  }
  return true;
}

/// The LAS offset (the rounded box centre of the file coordinates unless given); false when a
/// point is not finite or the extent does not fit in 32-bit integers at the scale.
bool
chooseOffset(const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin, const SaveOptions& o,
             Eigen::Vector3d& offset, std::string& error)
{
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const auto& p : cloud) {
    const Eigen::Vector3d x = p.getVector3fMap().cast<double>() + origin;
    if (!x.allFinite()) {
      error = "the cloud holds a NaN/inf point, which LAS cannot store";
      return false;
    }
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const bool empty = cloud.empty();
  offset = o.las_offset;
  if (!o.las_use_offset)
    offset = empty ? Eigen::Vector3d::Zero() : Eigen::Vector3d((0.5 * (lo + hi)).array().round());
  for (int k = 0; k < 3 && !empty; ++k) {
    const double a = (lo[k] - offset[k]) / o.las_scale[k], b = (hi[k] - offset[k]) / o.las_scale[k];
    if (std::max(std::abs(a), std::abs(b)) > 2147483000.0) {
      error = std::string("the ") + "xyz"[k] +
              " extent does not fit in 32-bit LAS integers at this scale; use a larger scale";
      return false;
    }
  }
  return true;
}

/// The VLRs to write: those that describe the input's records (extra bytes, LASzip, COPC's octree)
/// would lie about ours and are dropped; false when one is too large for a VLR.
bool
keptVlrs(const SaveOptions& o, std::vector<const LasVlr*>& vlrs, std::size_t& bytes, std::string& error)
{
  vlrs.clear();
  bytes = 0;
  for (const auto& v : o.las_vlrs) {
    if ((v.user_id == "LASF_Spec" && v.record_id == 4) || v.user_id == "laszip encoded" ||
        v.user_id == "copc")
      continue;
    if (v.data.size() > 65535) {
      error = "VLR " + v.user_id + "/" + std::to_string(v.record_id) + " exceeds 65535 bytes";
      return false;
    }
    vlrs.push_back(&v);
    bytes += las::kVlrHeaderSize + v.data.size();
  }
  return true;
}

/// What the header says about the records: quantised bounds and points per return number.
struct RecordSummary
{
  las::IntegerBox box;
  std::uint64_t by_return[15] = {};
};

/// One point record of \a format at \a r.
void
putRecord(const PointLiDAR& p, const Eigen::Vector3d& origin, const Eigen::Vector3d& offset,
          const SaveOptions& o, int format, std::uint8_t* r, RecordSummary& sum)
{
  for (int k = 0; k < 3; ++k) {
    const double x = static_cast<double>(p.data[k]) + origin[k];
    const auto q = static_cast<std::int32_t>(std::llround((x - offset[k]) / o.las_scale[k]));
    las::put<std::int32_t>(r + 4 * k, q);
    sum.box.add(k, q);
  }
  const float in = p.intensity;
  las::put<std::uint16_t>(
      r + 12, !(in > 0.f) ? 0 : (in >= 65535.f ? 65535 : static_cast<std::uint16_t>(std::lround(in))));
  if (format >= 6) {
    r[14] = static_cast<std::uint8_t>((p.return_number & 0x0F) | (p.number_of_returns << 4));
    r[16] = p.classification;
    las::put<std::uint16_t>(r + 20, p.point_source_id);
  } else {
    r[14] = static_cast<std::uint8_t>((p.return_number & 0x07) | ((p.number_of_returns & 0x07) << 3));
    r[15] = p.classification & 0x1F;
    las::put<std::uint16_t>(r + 18, p.point_source_id);
  }
  if (const std::size_t gps_offset = las::gpsTimeOffset(format))
    las::put<double>(r + gps_offset, p.gps_time);
  if (p.return_number >= 1 && p.return_number <= 15)
    ++sum.by_return[p.return_number - 1];
}

/// The public header of \a n records after \a vlr_count VLRs.
void
putHeader(std::uint8_t* h, std::size_t n, std::size_t vlr_count, std::size_t offset_to_points,
          const Eigen::Vector3d& offset, const RecordSummary& sum, const SaveOptions& o)
{
  const int format = o.las_point_format, minor = o.las_minor_version;
  std::memcpy(h, "LASF", 4);
  std::uint16_t encoding = 0;
  if (minor >= 2 && o.las_adjusted_standard_gps_time)
    encoding |= 1;
  const bool wkt_vlr = std::any_of(o.las_vlrs.begin(), o.las_vlrs.end(), [](const LasVlr& v) {
    return v.user_id == "LASF_Projection" && v.record_id == 2112;
  });
  if (minor >= 4 && (format >= 6 || wkt_vlr))
    encoding |= 1 << 4;  // LAS 1.4: the CRS is WKT (always so for formats 6-10)
  las::put<std::uint16_t>(h + las::kGlobalEncoding, encoding);
  h[las::kVersionMajor] = 1;
  h[las::kVersionMinor] = static_cast<std::uint8_t>(minor);
  putString(h + las::kSystemId, "pcl_ls3d", 32);
  putString(h + las::kSoftware, "pcl_ls3d io", 32);
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  las::put<std::uint16_t>(h + las::kCreationDay, static_cast<std::uint16_t>(utc.tm_yday + 1));
  las::put<std::uint16_t>(h + las::kCreationYear, static_cast<std::uint16_t>(utc.tm_year + 1900));
  las::put<std::uint16_t>(h + las::kHeaderSize, static_cast<std::uint16_t>(las::headerSizeFor(minor)));
  las::put<std::uint32_t>(h + las::kOffsetToPoints, static_cast<std::uint32_t>(offset_to_points));
  las::put<std::uint32_t>(h + las::kNumberOfVlrs, static_cast<std::uint32_t>(vlr_count));
  h[las::kPointFormat] = static_cast<std::uint8_t>(format);
  las::put<std::uint16_t>(h + las::kRecordLength, static_cast<std::uint16_t>(lasPointRecordLength(format)));
  // LAS 1.4 with formats 6-10: the legacy count and legacy by-return counts must be zero.
  const bool legacy = !(minor >= 4 && format >= 6) && n <= std::numeric_limits<std::uint32_t>::max();
  if (legacy) {
    las::put<std::uint32_t>(h + las::kLegacyCount, static_cast<std::uint32_t>(n));
    for (int r = 0; r < 5; ++r)
      las::put<std::uint32_t>(h + las::kLegacyByReturn + 4 * r, static_cast<std::uint32_t>(sum.by_return[r]));
  }
  for (int k = 0; k < 3; ++k) {
    las::put<double>(h + las::kScale + 8 * k, o.las_scale[k]);
    las::put<double>(h + las::kOffset + 8 * k, offset[k]);
    las::put<double>(h + las::kMaxX + 16 * k, n ? sum.box.hi[k] * o.las_scale[k] + offset[k] : 0.0);
    las::put<double>(h + las::kMaxX + 16 * k + 8, n ? sum.box.lo[k] * o.las_scale[k] + offset[k] : 0.0);
  }
  if (minor >= 4) {
    las::put<std::uint64_t>(h + las::kCount64, n);
    for (int r = 0; r < 15; ++r)
      las::put<std::uint64_t>(h + las::kByReturn64 + 8 * r, sum.by_return[r]);
  }
  // Waveform start (1.3+) and EVLR start/count (1.4) stay 0: none are written.
}

/// The VLRs, one after another from \a v.
void
putVlrs(std::uint8_t* v, const std::vector<const LasVlr*>& vlrs)
{
  for (const LasVlr* pv : vlrs) {
    const LasVlr& vlr = *pv;
    putString(v + 2, vlr.user_id, 16);
    las::put<std::uint16_t>(v + 18, vlr.record_id);
    las::put<std::uint16_t>(v + 20, static_cast<std::uint16_t>(vlr.data.size()));
    putString(v + 22, vlr.description, 32);
    if (!vlr.data.empty())
      std::memcpy(v + las::kVlrHeaderSize, vlr.data.data(), vlr.data.size());
    v += las::kVlrHeaderSize + vlr.data.size();
  }
}

}  // namespace

bool
writeLas(const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
         std::vector<std::uint8_t>& out, std::string& error, const SaveOptions& o)
{
  Eigen::Vector3d offset;
  std::vector<const LasVlr*> vlrs;
  std::size_t vlr_bytes = 0;
  if (!checkOptions(cloud, o, error) || !chooseOffset(cloud, origin, o, offset, error) ||
      !keptVlrs(o, vlrs, vlr_bytes, error))
    return false;
  const std::size_t header_size = las::headerSizeFor(o.las_minor_version);
  const std::size_t offset_to_points = header_size + vlr_bytes;
  if (offset_to_points > std::numeric_limits<std::uint32_t>::max()) {
    error = "VLRs too large";
    return false;
  }
  const std::size_t n = cloud.size(), record_length = lasPointRecordLength(o.las_point_format);
  out.assign(offset_to_points + n * record_length, 0);
  RecordSummary sum;
  for (std::size_t i = 0; i < n; ++i)
    putRecord(cloud[i], origin, offset, o, o.las_point_format,
              out.data() + offset_to_points + i * record_length, sum);
  putHeader(out.data(), n, vlrs.size(), offset_to_points, offset, sum, o);
  putVlrs(out.data() + header_size, vlrs);
  return true;
}

}  // namespace io
}  // namespace pcl_ls3d
