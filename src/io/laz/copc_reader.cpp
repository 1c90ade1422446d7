/// \file copc_reader.cpp
/// \brief COPC files as an octree: detection, the hierarchy, and box queries that decode only
///        the nodes they need (copc_reader.h).

#include "copc_reader.h"
#include "record_buffer.h"

#include "laszip_items.h"
#include "laz_chunk_reader.h"

#include <memory>
#include <new>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

const LasVlr*
findVlr(const std::vector<LasVlr>& vlrs, const char* user, std::uint16_t record)
{
  for (const LasVlr& v : vlrs)
    if (v.user_id == user && v.record_id == record)
      return &v;
  return nullptr;
}

std::string
nodeName(const CopcNode& n)
{
  return "COPC node " + std::to_string(n.key.level) + "-" + std::to_string(n.key.x) + "-" +
         std::to_string(n.key.y) + "-" + std::to_string(n.key.z);
}

/// One decoder per thread (each holds its models) and one record buffer per thread.
struct NodeWorkers
{
  std::vector<std::unique_ptr<ChunkDecoder>> decoders;
  std::vector<RecordBuffer> buffers;

  bool
  make(const LaszipVlr& vlr, int threads, std::string& error)
  {
    decoders.resize(static_cast<std::size_t>(threads));
    buffers.resize(static_cast<std::size_t>(threads));
    for (auto& d : decoders)
      if (!(d = makeChunkDecoder(vlr, error)))
        return false;
    return true;
  }
};

int
threadCount(std::uint64_t points)
{
#ifdef _OPENMP
  // Below this a parallel region costs more than it saves (as in the chunk reader).
  return points < 65536 ? 1 : omp_get_max_threads();
#else
  (void)points;
  return 1;
#endif
}

int
threadIndex()
{
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

/// Decodes node `n` into `buffer` and appends the records `keep` accepts to `part`.
bool
decodeNode(const std::uint8_t* data, const CopcNode& n, std::size_t record_length, ChunkDecoder& decoder,
           RecordBuffer& buffer, const RecordTest& keep, std::vector<std::uint8_t>& part, std::string& error)
{
  if (n.point_count > kMaxPointsPerByte * n.byte_size) {
    error = nodeName(n) + " claims " + std::to_string(n.point_count) + " points in " +
            std::to_string(n.byte_size) + " bytes";
    return false;
  }
  const std::size_t bytes = static_cast<std::size_t>(n.point_count) * record_length;
  std::uint8_t* out = buffer.reserve(bytes);
  if (!out) {
    error = nodeName(n) + ": no memory for the " + std::to_string(bytes) + " bytes of its points";
    return false;
  }
  const std::uint8_t* begin = data + n.offset;
  const std::size_t used = decoder.decode(begin, begin + n.byte_size, n.point_count, out, error);
  if (used == 0) {
    error = nodeName(n) + ": " + error;
    return false;
  }
  if (used != n.byte_size) {
    error = nodeName(n) + ": its points take " + std::to_string(used) + " bytes, the hierarchy says " +
            std::to_string(n.byte_size) + " (corrupt node)";
    return false;
  }
  for (std::size_t j = 0; j < n.point_count; ++j) {
    const std::uint8_t* r = out + j * record_length;
    if (keep(r))
      part.insert(part.end(), r, r + record_length);
  }
  return true;
}

}  // namespace

bool
isCopc(const LasHeaderInfo& h)
{
  return h.laz.compressed && h.laz.compressor == static_cast<int>(Compressor::LayeredChunked) &&
         h.laz.chunk_size == kVariableChunkSize && findVlr(h.vlrs, "copc", 1) != nullptr;
}

bool
openCopc(const std::uint8_t* data, std::size_t size, const LasHeaderInfo& h, CopcFile& copc,
         std::string& error)
{
  const LasVlr* vlr = findVlr(h.vlrs, "copc", 1);
  if (!vlr) {
    error = "the file has no COPC info VLR";
    return false;
  }
  return parseCopcInfo(vlr->data.data(), vlr->data.size(), copc.info, error) &&
         readCopcHierarchy(data, size, copc.info, h.point_count, copc.nodes, error);
}

CopcHeaderInfo
summariseCopc(const CopcFile& copc)
{
  CopcHeaderInfo s;
  s.present = true;
  s.center = copc.info.center;
  s.halfsize = copc.info.halfsize;
  s.spacing = copc.info.spacing;
  s.nodes = copc.nodes.size();
  for (const CopcLevelSummary& l : summariseLevels(copc.nodes))
    if (l.nodes > 0)
      s.levels.push_back({l.level, l.nodes, l.points});
  return s;
}

bool
readCopcNodes(const std::uint8_t* data, std::size_t size, const LasHeaderInfo& h, const CopcFile& copc,
              const CopcQuery& query, const RecordTest& keep, std::vector<std::vector<std::uint8_t>>& parts,
              RegionInfo& read, std::string& error)
{
  (void)size;  // every node was checked against the file by openCopc()
  const LasVlr* found = findVlr(h.vlrs, "laszip encoded", 22204);
  LaszipVlr vlr;
  if (!found ||
      !parseLaszipVlr(found->data.data(), found->data.size(), h.point_format, h.record_length, vlr, error))
    return (error = found ? error : "the COPC file has no LASzip VLR"), false;
  const std::vector<std::size_t> selected = selectNodes(copc.nodes, copc.info, query);
  read.copc = true;
  read.nodes = copc.nodes.size();
  read.nodes_read = selected.size();
  read.points_decoded = 0;
  for (std::size_t i : selected)
    read.points_decoded += copc.nodes[i].point_count;
  const int threads = threadCount(read.points_decoded);
  NodeWorkers workers;
  if (!workers.make(vlr, threads, error))
    return false;
  parts.assign(selected.size(), {});
  std::vector<std::string> errors(selected.size());
  std::vector<char> ok(selected.size(), 1);
  const auto n = static_cast<std::ptrdiff_t>(selected.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (threads > 1)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const auto t = static_cast<std::size_t>(threadIndex());
    const auto i = static_cast<std::size_t>(k);
    ok[i] = decodeNode(data, copc.nodes[selected[i]], h.record_length, *workers.decoders[t],
                       workers.buffers[t], keep, parts[i], errors[i]);
  }
  for (std::size_t i = 0; i < selected.size(); ++i)
    if (!ok[i])
      return (error = errors[i]), false;
  return true;
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
