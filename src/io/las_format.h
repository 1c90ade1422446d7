#pragma once
/// \file las_format.h
/// \brief Private LAS layout constants and little-endian byte access shared by reader and writer
///        (offsets from the ASPRS LAS 1.4 R15 specification, tables 3 and 7–17).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

namespace pcl_ls3d {
namespace io {
namespace las {

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "pcl_ls3d LAS IO assumes a little-endian host"
#endif

// Public header field offsets.
constexpr std::size_t kVersionMajor = 24, kVersionMinor = 25, kSystemId = 26, kSoftware = 58;
constexpr std::size_t kFileSourceId = 4, kGlobalEncoding = 6, kCreationDay = 90, kCreationYear = 92;
constexpr std::size_t kHeaderSize = 94, kOffsetToPoints = 96, kNumberOfVlrs = 100;
constexpr std::size_t kPointFormat = 104, kRecordLength = 105, kLegacyCount = 107;
constexpr std::size_t kLegacyByReturn = 111, kScale = 131, kOffset = 155;
constexpr std::size_t kMaxX = 179;           // then minX, maxY, minY, maxZ, minZ (doubles)
constexpr std::size_t kWaveformStart = 227;  // 1.3+
constexpr std::size_t kEvlrStart = 235, kEvlrCount = 243, kCount64 = 247, kByReturn64 = 255;  // 1.4

constexpr std::size_t kHeaderSize10 = 227, kHeaderSize13 = 235, kHeaderSize14 = 375;
constexpr std::size_t kVlrHeaderSize = 54, kEvlrHeaderSize = 60;

/// Header size a version requires.
inline std::size_t
headerSizeFor(int minor)
{
  return minor >= 4 ? kHeaderSize14 : (minor == 3 ? kHeaderSize13 : kHeaderSize10);
}

/// Byte offset of the GPS time in a record, or 0 when the format has none.
inline std::size_t
gpsTimeOffset(int format)
{
  if (format == 1 || (format >= 3 && format <= 5))
    return 20;
  if (format >= 6)
    return 22;
  return 0;
}

/// Bounds of the records' integer X, Y, Z (lo > hi while empty): what the header's min/max
/// are made of.
struct IntegerBox
{
  std::int32_t lo[3] = {std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::max(),
                        std::numeric_limits<std::int32_t>::max()};
  std::int32_t hi[3] = {std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::min(),
                        std::numeric_limits<std::int32_t>::min()};

  void
  add(int k, std::int32_t v)
  {
    lo[k] = std::min(lo[k], v);
    hi[k] = std::max(hi[k], v);
  }
};

template <typename T>
inline T
get(const std::uint8_t* p)
{
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

template <typename T>
inline void
put(std::uint8_t* p, T v)
{
  std::memcpy(p, &v, sizeof(T));
}

}  // namespace las
}  // namespace io
}  // namespace pcl_ls3d
