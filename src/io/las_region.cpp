/// \file las_region.cpp
/// \brief Box queries on LAS, LAZ and COPC files (las_region.h).

#include "las_region.h"

#include "las_format.h"
#include "las_header.h"
#include "laz/copc_reader.h"
#include "laz/laz_chunk_reader.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <cmath>

namespace pcl_ls3d {
namespace io {
namespace las {

namespace {

using Parts = std::vector<std::vector<std::uint8_t>>;

/// The records of an uncompressed file inside the region.
void
gatherLas(const std::uint8_t* data, const LasHeaderInfo& h, const Region& region, Parts& parts,
          RegionInfo& read)
{
  parts.assign(1, {});
  const std::uint8_t* block = data + h.offset_to_points;
  for (std::uint64_t i = 0; i < h.point_count; ++i) {
    const std::uint8_t* r = block + i * h.record_length;
    if (insideRegion(r, h, region))
      parts[0].insert(parts[0].end(), r, r + h.record_length);
  }
  read.points_decoded = h.point_count;
}

/// The records of a LAZ file inside the region, decoded chunk by chunk (in parallel when it has
/// a chunk table): only one batch of decoded chunks is held beside the records kept.
bool
gatherLaz(const std::uint8_t* data, std::size_t size, const LasHeaderInfo& h, const Region& region,
          Parts& parts, RegionInfo& read, std::string& error)
{
  laz::LazChunkReader reader;
  if (!reader.open(data, size, h, error))
    return false;
  parts.assign(reader.chunkCount(), {});
  const auto visit = [&](std::size_t chunk, const std::uint8_t* records, std::string&) {
    for (std::uint64_t j = 0; j < reader.chunkPoints(chunk); ++j) {
      const std::uint8_t* r = records + j * h.record_length;
      if (insideRegion(r, h, region))
        parts[chunk].insert(parts[chunk].end(), r, r + h.record_length);
    }
    return true;
  };
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  if (!reader.forEachChunk(threads, nullptr, visit, error))
    return false;
  read.points_decoded = h.point_count;
  return true;
}

/// The records of a COPC file inside the region, from the nodes whose cube meets it.
bool
gatherCopc(const std::uint8_t* data, std::size_t size, const LasHeaderInfo& h, const Region& region,
           Parts& parts, RegionInfo& read, std::string& error)
{
  laz::CopcFile copc;
  if (!laz::openCopc(data, size, h, copc, error))
    return false;
  laz::CopcQuery query;
  query.box = region.box;
  query.use_z = region.use_z;
  query.max_level = region.max_level;
  // A writer may round a point up to a quantum outside its node's cube.
  query.slack = h.scale.cwiseAbs().maxCoeff();
  const auto keep = [&](const std::uint8_t* r) { return insideRegion(r, h, region); };
  return laz::readCopcNodes(data, size, h, copc, query, keep, parts, read, error);
}

/// The LAS file of the kept records: the input's header, VLRs and EVLRs (less what described
/// its compression), with the counts and bounds of these records.
void
assemble(const std::uint8_t* data, const LasHeaderInfo& h, const Parts& parts, std::vector<std::uint8_t>& las)
{
  las = rebuildHead(data, h, {});
  IntegerBox box;
  std::uint64_t n = 0, by_return[15] = {};
  for (const std::vector<std::uint8_t>& part : parts) {
    for (std::size_t at = 0; at < part.size(); at += h.record_length) {
      const std::uint8_t* r = part.data() + at;
      for (int k = 0; k < 3; ++k)
        box.add(k, get<std::int32_t>(r + 4 * k));
      const int ret = h.point_format >= 6 ? (r[14] & 0x0F) : (r[14] & 0x07);
      if (ret >= 1)
        ++by_return[ret - 1];
      ++n;
    }
  }
  writeBounds(las, h, box, n == 0);
  writeCounts(las, h, n, by_return);
  if (h.version_minor >= 3)  // no waveform data follows the records kept
    put<std::uint64_t>(las.data() + kWaveformStart, 0);
  for (const std::vector<std::uint8_t>& part : parts)
    las.insert(las.end(), part.begin(), part.end());
  appendEvlrs(data, h, las);
}

}  // namespace

bool
checkRegion(const Region& region, std::string& error)
{
  const int dims = region.use_z ? 3 : 2;
  const Eigen::Vector3d lo = region.box.min(), hi = region.box.max();
  if (!lo.head(dims).allFinite() || !hi.head(dims).allFinite() ||
      (lo.head(dims).array() > hi.head(dims).array()).any()) {
    error = "the region's box is not finite or its minimum exceeds its maximum";
    return false;
  }
  return true;
}

bool
insideRegion(const std::uint8_t* r, const LasHeaderInfo& h, const Region& region)
{
  const int dims = region.use_z ? 3 : 2;
  for (int k = 0; k < dims; ++k) {
    const double x = get<std::int32_t>(r + 4 * k) * h.scale[k] + h.offset[k];
    if (!(x >= region.box.min()[k] && x <= region.box.max()[k]))
      return false;
  }
  return true;
}

bool
extractRegion(const std::uint8_t* data, std::size_t size, const LasHeaderInfo& h, const Region& region,
              std::vector<std::uint8_t>& las, RegionInfo& read, std::string& error)
{
  read = RegionInfo();
  read.applied = true;
  if (!checkRegion(region, error))
    return false;
  const bool copc = laz::isCopc(h);
  if (region.max_level >= 0 && !copc) {
    error = "a maximum octree level needs a COPC file (.copc.laz); this one has no octree";
    return false;
  }
  Parts parts;
  const bool ok = copc               ? gatherCopc(data, size, h, region, parts, read, error)
                  : h.laz.compressed ? gatherLaz(data, size, h, region, parts, read, error)
                                     : (gatherLas(data, h, region, parts, read), true);
  if (!ok)
    return false;
  assemble(data, h, parts, las);
  return true;
}

}  // namespace las
}  // namespace io
}  // namespace pcl_ls3d
