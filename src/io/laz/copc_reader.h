#pragma once
/// \file copc_reader.h
/// \brief Private: a `.copc.laz` file read as an octree. A file is COPC when it holds the COPC
///        info VLR (user "copc", record 1) and is layered LAZ with variable-size chunks; each
///        node of its hierarchy is then one chunk, which is decoded on its own. A box query
///        decodes only the nodes whose cube meets the box, in parallel.

#include <pcl_ls3d/io/cloud_io.h>

#include "copc_hierarchy.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace laz {

/// \brief The octree of an opened COPC file.
struct CopcFile
{
  CopcInfo info;
  std::vector<CopcNode> nodes;  ///< nodes holding points, in file order
};

/// Is the file (its header parsed by las::parseHeader) COPC? A COPC info VLR in a file that is not
/// layered LAZ with variable chunks describes nothing readable and is ignored.
bool
isCopc(const LasHeaderInfo& h);

/// Reads the info VLR and the whole hierarchy of a COPC file, every page and node checked
/// against the file. False with a one-line reason.
bool
openCopc(const std::uint8_t* data, std::size_t size, const LasHeaderInfo& h, CopcFile& copc,
         std::string& error);

/// The summary CloudInfo::las.copc carries (levels, nodes, points per level).
CopcHeaderInfo
summariseCopc(const CopcFile& copc);

/// Keeps a decoded record (true) or drops it.
using RecordTest = std::function<bool(const std::uint8_t* record)>;

/// Decodes the nodes `query` selects and keeps the records `keep` accepts: parts[k] holds the
/// kept records of the k-th node read, in file order. `read` counts the nodes and points
/// decoded. False with a one-line reason naming the node when one does not decode.
bool
readCopcNodes(const std::uint8_t* data, std::size_t size, const LasHeaderInfo& h, const CopcFile& copc,
              const CopcQuery& query, const RecordTest& keep, std::vector<std::vector<std::uint8_t>>& parts,
              RegionInfo& read, std::string& error);

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
