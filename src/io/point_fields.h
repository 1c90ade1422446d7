#pragma once
/// \file point_fields.h
/// \brief Private: what the PCD and PLY readers share — typed scalars read from raw bytes in
///        either byte order, the mapping of field names onto PointLiDAR, short quotes of input
///        text for error messages, and strict unsigned integers for header counts.

#include <pcl_ls3d/point_types.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace detail {

enum class Scalar : std::uint8_t
{
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Int64,
  UInt64,
  Float32,
  Float64
};

/// Bytes of one value.
std::size_t
scalarSize(Scalar type);

/// The value at `p` (any alignment), converted to double.
double
readScalar(const std::uint8_t* p, Scalar type, bool big_endian);

/// What a named field fills in a PointLiDAR (X, Y, Z go to the double coordinates).
enum class Attribute : std::uint8_t
{
  None,
  X,
  Y,
  Z,
  Intensity,
  GpsTime,
  PointSourceId,
  Classification,
  ReturnNumber,
  NumberOfReturns
};

/// One attribute per field name, in order: x y z intensity gps_time point_source_id
/// classification (or label when there is no classification and `label_is_class`: a
/// SEGMENTS.pcd's labels are segment ids) return_number number_of_returns; a repeated name maps
/// only its first field; anything else is Attribute::None. `mapped` gets the names of the
/// mapped fields in the order above (CloudInfo::fields).
std::vector<Attribute>
mapAttributes(const std::vector<std::string>& names, std::vector<std::string>& mapped,
              bool label_is_class = true);

/// True when `attributes` maps x, y and z.
bool
hasXyz(const std::vector<Attribute>& attributes);

/// Stores `value` into `xyz` (X, Y, Z) or the point's attribute; integer attributes are rounded
/// and clamped to their range, NaN becomes 0.
void
setAttribute(Attribute a, double value, PointLiDAR& point, double* xyz);

/// `text` with control bytes shown as '?' (a newline in a file's string or name would break the
/// one-line error).
std::string
printable(std::string_view text);

/// printable() of at most the first `max_chars` bytes of `text`.
std::string
clip(std::string_view text, std::size_t max_chars = 40);

/// clip() in quotes, followed by the full length when it was cut: 'abc...' (1000 characters).
std::string
quote(std::string_view text, std::size_t max_chars = 40);

/// Digits only (no sign, no spaces), at most `max`; false otherwise.
bool
parseCount(std::string_view text, std::uint64_t max, std::uint64_t& value);

/// A number in the C locale (from_chars; a leading '+' allowed; nan and inf accepted).
bool
parseDouble(std::string_view text, double& value);

/// Splits `line` on spaces, tabs and '\r' into views of `line`.
void
splitTokens(std::string_view line, std::vector<std::string_view>& tokens);

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
