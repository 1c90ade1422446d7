#pragma once
/// \file las_records.h
/// \brief Raw, read-only access to the point records of a LAS 1.0–1.4 file (mapped, no copy;
///        a LAZ file is decompressed into memory): the header as validated by readLasHeader(), and per record the
///        quantised X, Y, Z, the file coordinates in double, the classification with its flags
///        (synthetic, key-point, withheld, overlap) and the point-source id. The strip adjustment
///        reads its strips this way and rewrites them record by record (las_rewrite.h), so every
///        byte it does not correct is carried over unchanged.

#include <pcl_ls3d/io/cloud_io.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace pcl_ls3d {
namespace io {

/// \brief Classification flags of a record (LAS 1.4 R15, tables 7 and 8).
struct LasPointFlags
{
  bool synthetic = false, key_point = false, withheld = false, overlap = false;
};

/// \brief An opened LAS file. Move-only; the mapping lives as long as the object.
class LasRecordFile
{
public:
  LasRecordFile();
  ~LasRecordFile();
  LasRecordFile(LasRecordFile&&) noexcept;
  LasRecordFile&
  operator=(LasRecordFile&&) noexcept;

  /// Maps and validates the file (damaged files are refused with a one-line reason). A LAZ file
  /// is decompressed into memory whole: header(), data() and the records are then those of the
  /// LAS file it compresses (no LASzip VLR, no COPC VLR or hierarchy, no compression bits).
  /// With a `region`, only the records inside its box are kept (a COPC file decodes only the
  /// octree nodes the box meets): the file is then the LAS file of those records, with the
  /// input's header, VLRs and EVLRs and their counts and bounds (see regionInfo()).
  bool
  open(const std::string& path, std::string& error, const Region* region = nullptr);

  /// What a region given to open() read (nodes, points decoded); not applied without one.
  const RegionInfo&
  regionInfo() const;

  const LasHeaderInfo&
  header() const;
  std::size_t
  size() const;  ///< number of point records
  /// The whole file (header, VLRs, records and whatever follows them).
  const std::uint8_t*
  data() const;
  std::size_t
  bytes() const;
  /// Record i (record_length bytes).
  const std::uint8_t*
  record(std::size_t i) const;

  /// Quantised X, Y, Z of record i.
  Eigen::Vector3i
  quantised(std::size_t i) const;
  /// File coordinates X·scale + offset, in double.
  Eigen::Vector3d
  coordinates(std::size_t i) const;
  std::uint8_t
  classification(std::size_t i) const;
  LasPointFlags
  flags(std::size_t i) const;
  std::uint16_t
  pointSourceId(std::size_t i) const;
  /// Return number (1-based; 0 in damaged files).
  int
  returnNumber(std::size_t i) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace io
}  // namespace pcl_ls3d
