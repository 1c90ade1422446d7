/// \file test_copc_hierarchy.cpp
/// \brief The COPC hierarchy reader: real files' hierarchies account for every point; node cubes
///        nest; box selection agrees with a brute-force check; hostile hierarchies (loops, pages
///        or chunks outside the file, keys outside the octree, too many points) are refused.

#include "io/las_format.h"
#include "io/laz/copc_hierarchy.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <map>
#include <tuple>

using namespace pcl_ls3d::io;
using namespace pcl_ls3d::io::laz;

namespace {

const std::string kLaz = std::string(PCL_LS3D_SHARED_DATA_DIR) + "/laz/";

std::vector<std::uint8_t>
readBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

/// The COPC info VLR payload of a LAS 1.4 file (the first VLR, as COPC requires).
bool
copcInfoOf(const std::vector<std::uint8_t>& f, CopcInfo& info, std::uint64_t& count)
{
  const std::size_t header = las::get<std::uint16_t>(f.data() + las::kHeaderSize);
  count = las::get<std::uint64_t>(f.data() + las::kCount64);
  std::string error;
  return parseCopcInfo(f.data() + header + las::kVlrHeaderSize, f.size() - header - 54, info, error);
}

void
putEntry(std::vector<std::uint8_t>& f, std::size_t at, VoxelKey k, std::uint64_t offset, std::int32_t size,
         std::int32_t count)
{
  las::put<std::int32_t>(f.data() + at, k.level);
  las::put<std::int32_t>(f.data() + at + 4, k.x);
  las::put<std::int32_t>(f.data() + at + 8, k.y);
  las::put<std::int32_t>(f.data() + at + 12, k.z);
  las::put<std::uint64_t>(f.data() + at + 16, offset);
  las::put<std::int32_t>(f.data() + at + 24, size);
  las::put<std::int32_t>(f.data() + at + 28, count);
}

/// A 1000-byte "file" with a root page at 800 holding `entries` (filled by the test) and a
/// root cube of half-size 10 about the origin.
struct FakeCopc
{
  std::vector<std::uint8_t> bytes = std::vector<std::uint8_t>(1000, 0);
  CopcInfo info;
  FakeCopc(std::size_t entries)
  {
    info.halfsize = 10.0;
    info.root_page_offset = 800;
    info.root_page_size = 32 * entries;
  }
  bool
  read(std::vector<CopcNode>& nodes, std::string& error, std::uint64_t points = 1000) const
  {
    return readCopcHierarchy(bytes.data(), bytes.size(), info, points, nodes, error);
  }
};

}  // namespace

TEST(CopcHierarchy, RealFilesAccountForEveryPoint)
{
  for (const char* name :
       {"pdal/lone-star.copc.laz", "laspy/simple.copc.laz", "pdal/1.2-with-color.copc.laz"}) {
    const std::vector<std::uint8_t> f = readBytes(kLaz + name);
    if (f.empty())
      GTEST_SKIP() << "shared data absent: " << kLaz + name;
    CopcInfo info;
    std::uint64_t count = 0;
    ASSERT_TRUE(copcInfoOf(f, info, count)) << name;
    std::vector<CopcNode> nodes;
    std::string error;
    ASSERT_TRUE(readCopcHierarchy(f.data(), f.size(), info, count, nodes, error)) << error;
    std::uint64_t sum = 0;
    std::map<std::tuple<int, int, int, int>, bool> keys;
    for (const CopcNode& n : nodes) {
      sum += n.point_count;
      keys[{n.key.level, n.key.x, n.key.y, n.key.z}] = true;
      EXPECT_LE(n.offset + n.byte_size, f.size());
    }
    EXPECT_EQ(sum, count) << name;
    // Every non-root node's parent cube holds it (the octree nests).
    for (const CopcNode& n : nodes) {
      if (n.key.level == 0)
        continue;
      const VoxelKey parent{n.key.level - 1, n.key.x / 2, n.key.y / 2, n.key.z / 2};
      Eigen::AlignedBox3d outer = nodeBounds(info, parent);
      outer.min().array() -= 1e-9 * info.halfsize;  // the two cubes are rounded separately
      outer.max().array() += 1e-9 * info.halfsize;
      EXPECT_TRUE(outer.contains(nodeBounds(info, n.key)));
    }
    const std::vector<CopcLevelSummary> levels = summariseLevels(nodes);
    ASSERT_FALSE(levels.empty());
    EXPECT_EQ(levels[0].nodes, 1u) << "one root node";
  }
}

TEST(CopcHierarchy, SelectionMatchesBruteForce)
{
  const std::vector<std::uint8_t> f = readBytes(kLaz + "pdal/lone-star.copc.laz");
  if (f.empty())
    GTEST_SKIP() << "shared data absent: " << kLaz;
  CopcInfo info;
  std::uint64_t count = 0;
  ASSERT_TRUE(copcInfoOf(f, info, count));
  std::vector<CopcNode> nodes;
  std::string error;
  ASSERT_TRUE(readCopcHierarchy(f.data(), f.size(), info, count, nodes, error)) << error;
  const Eigen::Vector3d c = info.center;
  const double h = info.halfsize;
  // Nothing, a corner, a thin slab, everything.
  const Eigen::AlignedBox3d boxes[] = {
      {c + Eigen::Vector3d::Constant(3 * h), c + Eigen::Vector3d::Constant(4 * h)},
      {c - Eigen::Vector3d::Constant(h), c - Eigen::Vector3d::Constant(0.9 * h)},
      {c - Eigen::Vector3d(h, 0.01, h), c + Eigen::Vector3d(h, 0.01, h)},
      {c - Eigen::Vector3d::Constant(h), c + Eigen::Vector3d::Constant(h)}};
  std::size_t sizes[4];
  for (int b = 0; b < 4; ++b) {
    CopcQuery q{boxes[b], true, -1};
    const std::vector<std::size_t> got = selectNodes(nodes, info, q);
    std::size_t expected = 0;
    for (const CopcNode& n : nodes) {
      const Eigen::AlignedBox3d cube = nodeBounds(info, n.key);
      const bool meets = (cube.min().array() <= boxes[b].max().array()).all() &&
                         (boxes[b].min().array() <= cube.max().array()).all();
      expected += meets;
    }
    EXPECT_EQ(got.size(), expected) << "box " << b;
    sizes[b] = got.size();
  }
  EXPECT_EQ(sizes[0], 0u);
  EXPECT_EQ(sizes[3], nodes.size());
  EXPECT_LT(sizes[1], nodes.size());
  // A level limit keeps only the coarse levels.
  CopcQuery coarse{boxes[3], true, 1};
  for (std::size_t i : selectNodes(nodes, info, coarse))
    EXPECT_LE(nodes[i].key.level, 1);
}

TEST(CopcHierarchy, HostileHierarchiesAreRefused)
{
  std::vector<CopcNode> nodes;
  std::string error;
  {  // a page that names itself
    FakeCopc c(1);
    putEntry(c.bytes, 800, {0, 0, 0, 0}, 800, 32, -1);
    EXPECT_FALSE(c.read(nodes, error));
    EXPECT_NE(error.find("loop"), std::string::npos) << error;
  }
  {  // a child page beyond the end of the file
    FakeCopc c(1);
    putEntry(c.bytes, 800, {1, 0, 0, 0}, 5000, 32, -1);
    EXPECT_FALSE(c.read(nodes, error));
    EXPECT_NE(error.find("outside the file"), std::string::npos) << error;
  }
  {  // a chunk running past the end
    FakeCopc c(1);
    putEntry(c.bytes, 800, {0, 0, 0, 0}, 900, 200, 10);
    EXPECT_FALSE(c.read(nodes, error));
  }
  {  // a key outside the octree
    FakeCopc c(1);
    putEntry(c.bytes, 800, {1, 2, 0, 0}, 100, 10, 10);
    EXPECT_FALSE(c.read(nodes, error));
    EXPECT_NE(error.find("outside the octree"), std::string::npos) << error;
  }
  {  // more points than the header
    FakeCopc c(2);
    putEntry(c.bytes, 800, {0, 0, 0, 0}, 100, 10, 600);
    putEntry(c.bytes, 832, {1, 0, 0, 0}, 200, 10, 600);
    EXPECT_FALSE(c.read(nodes, error));
  }
  {  // the root page itself outside the file
    FakeCopc c(1);
    c.info.root_page_offset = 990;
    EXPECT_FALSE(c.read(nodes, error));
  }
  {  // a well-formed two-page hierarchy is read whole
    FakeCopc c(2);
    putEntry(c.bytes, 800, {0, 0, 0, 0}, 100, 10, 5);
    putEntry(c.bytes, 832, {1, 1, 0, 1}, 700, 32, -1);
    putEntry(c.bytes, 700, {2, 3, 1, 2}, 300, 20, 7);
    ASSERT_TRUE(c.read(nodes, error)) << error;
    ASSERT_EQ(nodes.size(), 2u);
    EXPECT_EQ(nodes[0].point_count + nodes[1].point_count, 12u);
  }
}
