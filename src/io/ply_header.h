#pragma once
/// \file ply_header.h
/// \brief Private: the PLY header (format, elements, properties). Nothing here allocates in
///        proportion to a count in the file.

#include "point_fields.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace detail {

enum class PlyFormat
{
  Ascii,
  BinaryLittleEndian,
  BinaryBigEndian
};

struct PlyProperty
{
  std::string name;
  bool list = false;
  Scalar type = Scalar::Float32;      ///< the value type (a list's item type)
  Scalar count_type = Scalar::UInt8;  ///< a list's count type (an integer type)
};

struct PlyElement
{
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;

  /// Bytes of one item in a binary file when it has no list; else the smallest item (empty lists).
  std::size_t
  minimumBytes() const;

  bool
  hasList() const;
};

struct PlyHeader
{
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;   ///< first byte after the end_header line
  std::size_t header_lines = 0;  ///< lines up to and including end_header
  std::string crs_wkt;           ///< of the first "comment pcl_ls3d crs WKT" line (empty: none)
};

/// Parses and checks the header; false with a one-line reason ("PLY ...").
bool
parsePlyHeader(const std::uint8_t* data, std::size_t size, PlyHeader& h, std::string& error);

/// Sets `error` to "PLY " + message; returns false.
bool
plyFail(std::string& error, const std::string& message);

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
