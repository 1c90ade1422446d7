#pragma once
/// \file copc_hierarchy.h
/// \brief Private: the COPC info VLR and the octree hierarchy EVLR of a `.copc.laz` file, read
///        with every page and node checked against the file, and the selection of the nodes a
///        2-D or 3-D box query needs. Each data node is one variable-sized layered LAZ chunk.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace laz {

/// \brief The COPC info VLR (user "copc", record 1): the octree's root cube and where the
///        hierarchy's root page is.
struct CopcInfo
{
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double halfsize = 0.0;  ///< half the root cube's edge (file units)
  double spacing = 0.0;   ///< point spacing at the root level
  std::uint64_t root_page_offset = 0, root_page_size = 0;
  double gps_time_min = 0.0, gps_time_max = 0.0;
};

/// \brief An octree cell: level 0 is the root; x, y, z count cells of edge 2·halfsize / 2^level.
struct VoxelKey
{
  std::int32_t level = 0, x = 0, y = 0, z = 0;
};

/// \brief A hierarchy entry that holds points: one layered LAZ chunk in the file.
struct CopcNode
{
  VoxelKey key;
  std::uint64_t offset = 0;     ///< absolute file offset of the chunk
  std::uint32_t byte_size = 0;  ///< bytes of the chunk
  std::uint32_t point_count = 0;
};

/// The COPC info VLR's payload (160 bytes). False with a one-line reason.
bool
parseCopcInfo(const std::uint8_t* data, std::size_t size, CopcInfo& info, std::string& error);

/// Reads the hierarchy from the whole file's bytes: every page reachable from the root page,
/// each read once (a page referenced twice, a loop, is an error), every page and chunk inside
/// the file, keys inside the octree. Returns the nodes that hold points. The node point counts
/// must not add up to more than `file_point_count`. False with a one-line reason.
bool
readCopcHierarchy(const std::uint8_t* file, std::size_t file_size, const CopcInfo& info,
                  std::uint64_t file_point_count, std::vector<CopcNode>& nodes, std::string& error);

/// The cube of a key, in file coordinates.
Eigen::AlignedBox3d
nodeBounds(const CopcInfo& info, const VoxelKey& key);

/// \brief A spatial query: a box in file coordinates (x, y only when !use_z), down to
///        max_level (< 0: every level).
struct CopcQuery
{
  Eigen::AlignedBox3d box;
  bool use_z = false;
  int max_level = -1;
  /// Grows every node's cube by this much (file units): a writer may place a point up to half a
  /// quantisation step outside its node's cube, and such a point must not be missed.
  double slack = 0.0;
};

/// Indices of the nodes whose cube meets the query's box, at the query's levels.
std::vector<std::size_t>
selectNodes(const std::vector<CopcNode>& nodes, const CopcInfo& info, const CopcQuery& query);

/// \brief Nodes and points per octree level (what `pcl_ls3d_info` prints).
struct CopcLevelSummary
{
  int level = 0;
  std::size_t nodes = 0;
  std::uint64_t points = 0;
};

std::vector<CopcLevelSummary>
summariseLevels(const std::vector<CopcNode>& nodes);

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
