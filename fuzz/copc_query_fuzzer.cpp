/// \file copc_query_fuzzer.cpp
/// \brief libFuzzer target for the COPC hierarchy reader and box queries: arbitrary bytes are
///        described by readLasHeader() (which reads a COPC file's info VLR and its whole
///        hierarchy: pages, loops, nodes outside the file or the octree) and then queried with
///        readLas() and a region: the whole header box, its lower-left quarter, a box beside it
///        and a thin slab in 3-D, down to a level the input's size picks. A COPC file decodes only
///        the nodes its query selects; any other input (LAS, LAZ) is read through and filtered.
///        Every call returns true or false with one short line; every point kept lies in its box.

#include <pcl_ls3d/io/las_io.h>

#include "fuzz_checks.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

/// The query boxes, from the header's bounds (file coordinates).
std::vector<pcl_ls3d::io::Region>
queries(const pcl_ls3d::io::LasHeaderInfo& h, int level)
{
  const Eigen::Vector3d lo = h.min, hi = h.max, mid = 0.5 * (lo + hi), size = hi - lo;
  std::vector<pcl_ls3d::io::Region> q(4);
  q[0].box = Eigen::AlignedBox3d(lo, hi);
  q[1].box = Eigen::AlignedBox3d(lo, mid);
  q[2].box = Eigen::AlignedBox3d(hi + size, hi + 2 * size + Eigen::Vector3d::Ones());
  q[3].box = Eigen::AlignedBox3d(Eigen::Vector3d(lo.x(), mid.y(), lo.z()),
                                 Eigen::Vector3d(hi.x(), mid.y() + 0.01 * size.y(), hi.z()));
  q[3].use_z = true;
  for (auto& r : q)
    r.max_level = h.copc.present ? level : -1;
  return q;
}

void
checkInside(const pcl::PointCloud<pcl_ls3d::PointLiDAR>& cloud, const pcl_ls3d::io::CloudInfo& info,
            const pcl_ls3d::io::Region& r)
{
  const int dims = r.use_z ? 3 : 2;
  for (const auto& p : cloud) {
    const Eigen::Vector3d x = info.origin + p.getVector3fMap().cast<double>();
    for (int k = 0; k < dims; ++k) {
      // Local coordinates are floats: allow their rounding.
      const double slack = 1e-6 * std::abs(x[k] - info.origin[k]) + 1e-6;
      if (x[k] < r.box.min()[k] - slack || x[k] > r.box.max()[k] + slack) {
        std::fprintf(stderr, "fuzz check failed: a point outside its query box\n");
        std::abort();
      }
    }
  }
}

}  // namespace

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  pcl_ls3d::io::LasHeaderInfo h;
  std::string error;
  if (!pcl_ls3d::io::readLasHeader(data, size, h, error)) {
    if (error.empty() || error.size() > 400 || error.find('\n') != std::string::npos)
      std::abort();
    return 0;
  }
  if (!h.min.allFinite() || !h.max.allFinite() || (h.min.array() > h.max.array()).any())
    return 0;  // no box to query from
  std::uint64_t in_levels = 0;
  for (const auto& l : h.copc.levels)
    in_levels += l.points;
  if (h.copc.present && in_levels > h.point_count)
    std::abort();  // the hierarchy may not claim more points than the file
  for (const pcl_ls3d::io::Region& r : queries(h, static_cast<int>(size % 4) - 1)) {
    pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
    pcl_ls3d::io::CloudInfo info;
    pcl_ls3d::io::LoadOptions load;
    load.allow_empty = true;
    load.region = r;
    const bool ok = pcl_ls3d::io::readLas(data, size, cloud, info, error, load);
    pcl_ls3d_fuzz::checkResult(ok, error, cloud, info);
    if (!ok)
      continue;
    checkInside(cloud, info, r);
    if (info.region.copc && info.region.nodes_read > info.region.nodes)
      std::abort();
  }
  return 0;
}
