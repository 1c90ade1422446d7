/// \file copc_hierarchy.cpp
/// \brief COPC info and hierarchy reading (COPC 1.0 specification) and node selection.

#include "copc_hierarchy.h"

#include "io/las_format.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

constexpr std::size_t kInfoBytes = 160, kEntryBytes = 32;
/// Deeper than any real octree (2^40 cells across) and shallow enough that cell arithmetic
/// stays exact in double.
constexpr std::int32_t kMaxLevel = 40;

bool
keyInsideOctree(const VoxelKey& k)
{
  if (k.level < 0 || k.level > kMaxLevel)
    return false;
  const std::int64_t cells = std::int64_t{1} << k.level;
  auto inside = [cells](std::int32_t v) { return v >= 0 && v < cells; };
  return inside(k.x) && inside(k.y) && inside(k.z);
}

std::string
keyText(const VoxelKey& k)
{
  return std::to_string(k.level) + "-" + std::to_string(k.x) + "-" + std::to_string(k.y) + "-" +
         std::to_string(k.z);
}

/// A page waiting to be read: where it is and how many bytes it holds.
struct PageRef
{
  std::uint64_t offset, size;
};

bool
checkPage(const PageRef& page, std::size_t file_size, std::set<std::uint64_t>& seen, std::string& error)
{
  if (page.size % kEntryBytes != 0 || page.offset > file_size || page.size > file_size - page.offset) {
    error = "COPC hierarchy page at byte " + std::to_string(page.offset) + " of " +
            std::to_string(page.size) + " bytes lies outside the file or is not whole entries";
    return false;
  }
  if (!seen.insert(page.offset).second) {
    error = "COPC hierarchy page at byte " + std::to_string(page.offset) +
            " is referenced twice (a loop in the hierarchy)";
    return false;
  }
  return true;
}

/// Reads one page's entries: data nodes go to `nodes`, child pages to `pending`.
bool
readPage(const std::uint8_t* file, std::size_t file_size, const PageRef& page, std::vector<CopcNode>& nodes,
         std::vector<PageRef>& pending, std::uint64_t& points, std::string& error)
{
  for (std::uint64_t e = 0; e < page.size / kEntryBytes; ++e) {
    const std::uint8_t* p = file + page.offset + e * kEntryBytes;
    CopcNode node;
    node.key = {las::get<std::int32_t>(p), las::get<std::int32_t>(p + 4), las::get<std::int32_t>(p + 8),
                las::get<std::int32_t>(p + 12)};
    node.offset = las::get<std::uint64_t>(p + 16);
    const std::int32_t byte_size = las::get<std::int32_t>(p + 24);
    const std::int32_t count = las::get<std::int32_t>(p + 28);
    if (!keyInsideOctree(node.key)) {
      error = "COPC hierarchy entry " + keyText(node.key) + " lies outside the octree";
      return false;
    }
    if (count == -1) {
      pending.push_back({node.offset, static_cast<std::uint64_t>(std::max(byte_size, 0))});
      continue;
    }
    if (count < -1 || byte_size < 0) {
      error = "COPC hierarchy entry " + keyText(node.key) + " has a negative point count or size";
      return false;
    }
    if (count == 0)
      continue;
    node.byte_size = static_cast<std::uint32_t>(byte_size);
    node.point_count = static_cast<std::uint32_t>(count);
    if (node.offset > file_size || node.byte_size > file_size - node.offset) {
      error = "COPC node " + keyText(node.key) + " points at bytes outside the file";
      return false;
    }
    points += node.point_count;
    nodes.push_back(node);
  }
  return true;
}

}  // namespace

bool
parseCopcInfo(const std::uint8_t* data, std::size_t size, CopcInfo& info, std::string& error)
{
  if (size < kInfoBytes) {
    error = "the COPC info VLR is " + std::to_string(size) + " bytes, not 160";
    return false;
  }
  info.center = {las::get<double>(data), las::get<double>(data + 8), las::get<double>(data + 16)};
  info.halfsize = las::get<double>(data + 24);
  info.spacing = las::get<double>(data + 32);
  info.root_page_offset = las::get<std::uint64_t>(data + 40);
  info.root_page_size = las::get<std::uint64_t>(data + 48);
  info.gps_time_min = las::get<double>(data + 56);
  info.gps_time_max = las::get<double>(data + 64);
  if (!info.center.allFinite() || !std::isfinite(info.halfsize) || !(info.halfsize > 0.0)) {
    error = "the COPC info VLR has a non-finite centre or a half-size that is not positive";
    return false;
  }
  return true;
}

bool
readCopcHierarchy(const std::uint8_t* file, std::size_t file_size, const CopcInfo& info,
                  std::uint64_t file_point_count, std::vector<CopcNode>& nodes, std::string& error)
{
  nodes.clear();
  std::set<std::uint64_t> seen;
  std::vector<PageRef> pending{{info.root_page_offset, info.root_page_size}};
  std::uint64_t points = 0;
  while (!pending.empty()) {
    const PageRef page = pending.back();
    pending.pop_back();
    if (!checkPage(page, file_size, seen, error) ||
        !readPage(file, file_size, page, nodes, pending, points, error))
      return false;
    if (points > file_point_count) {
      error = "the COPC hierarchy holds more points than the header's " + std::to_string(file_point_count);
      return false;
    }
  }
  // File order, so a query reads the file front to back.
  std::sort(nodes.begin(), nodes.end(),
            [](const CopcNode& a, const CopcNode& b) { return a.offset < b.offset; });
  return true;
}

Eigen::AlignedBox3d
nodeBounds(const CopcInfo& info, const VoxelKey& key)
{
  const double edge = 2.0 * info.halfsize / std::ldexp(1.0, key.level);
  const Eigen::Vector3d lo =
      info.center - Eigen::Vector3d::Constant(info.halfsize) + edge * Eigen::Vector3d(key.x, key.y, key.z);
  return Eigen::AlignedBox3d(lo, lo + Eigen::Vector3d::Constant(edge));
}

std::vector<std::size_t>
selectNodes(const std::vector<CopcNode>& nodes, const CopcInfo& info, const CopcQuery& query)
{
  std::vector<std::size_t> selected;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (query.max_level >= 0 && nodes[i].key.level > query.max_level)
      continue;
    Eigen::AlignedBox3d cube = nodeBounds(info, nodes[i].key);
    cube.min().array() -= query.slack;
    cube.max().array() += query.slack;
    if (!query.use_z) {
      cube.min().z() = query.box.min().z();
      cube.max().z() = query.box.max().z();
    }
    // Points on a cube's upper face may belong to it (writers round), so touching counts.
    if (cube.intersects(query.box))
      selected.push_back(i);
  }
  return selected;
}

std::vector<CopcLevelSummary>
summariseLevels(const std::vector<CopcNode>& nodes)
{
  std::vector<CopcLevelSummary> levels;
  for (const CopcNode& n : nodes) {
    if (static_cast<std::size_t>(n.key.level) >= levels.size())
      levels.resize(n.key.level + 1);
    levels[n.key.level].level = n.key.level;
    ++levels[n.key.level].nodes;
    levels[n.key.level].points += n.point_count;
  }
  return levels;
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
