#pragma once
/// \file las_rewrite.h
/// \brief Rewrites a LAS file record by record with corrected coordinates: header, VLRs, every
///        record byte except X, Y, Z, and whatever follows the records (EVLRs, waveform data)
///        are copied unchanged; only X, Y, Z of moved records and the header bounds change (and,
///        when a subset of the records is written, the point counts and the offsets of what
///        follows the records). The strip adjustment writes its corrected strips this way, so
///        intensity, returns, flags, classification, GPS time, RGB/NIR, extra bytes and the CRS
///        survive byte for byte, whatever the point format. A LAZ input (opened by LasRecordFile)
///        can be written back as LAZ: the name of the output decides.

#include <pcl_ls3d/io/las_records.h>

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {

/// move(i, x): x holds the file coordinates of record i; return true (and the new coordinates
/// in x) to move it, false to copy the record unchanged.
using RecordMover = std::function<bool(std::size_t, Eigen::Vector3d&)>;

/// \brief What rewriteLas() wrote.
struct LasRewriteSummary
{
  std::size_t points = 0;  ///< records written
  std::size_t moved = 0;   ///< records whose X, Y, Z were replaced
};

/// Writes the records `selection` (indices into `in`, in the order given; null = all, in file
/// order) to `path`, moved by `move`. New coordinates are quantised with the input's scale and
/// offset; a coordinate outside the int32 range is an error. A `path` ending in .laz gets the
/// same file compressed (compressLas(): header, VLRs, EVLRs and every record byte kept, the
/// LASzip VLR added), any other name LAS. Refuses an existing `path` unless `overwrite`. False
/// with a one-line reason.
bool
rewriteLas(const LasRecordFile& in, const std::vector<std::size_t>* selection, const RecordMover& move,
           const std::string& path, LasRewriteSummary& summary, std::string& error, bool overwrite = false);

}  // namespace io
}  // namespace pcl_ls3d
