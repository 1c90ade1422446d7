#pragma once
/// \file assembly_groups.h
/// \brief Internal: what the object-assembly rules share (object_assembly.cpp,
///        roof_footprints.cpp): the union-find over segments, the point-level contacts, the
///        structural kinds. Not installed API.

#include <pcl_ls3d/segmentation/segment_kinds.h>

#include <Eigen/Core>

#include <algorithm>
#include <numeric>
#include <vector>

namespace pcl_ls3d {
namespace segmentation {
namespace detail {

/// Roofs and walls: the kinds a building is made of.
inline bool
structural(SegmentKind k)
{
  return k == SegmentKind::Solid || k == SegmentKind::Wall;
}

/// The point-level contacts the attachments look at.
struct Contacts
{
  const std::vector<Eigen::Vector3f>& points;
  const std::vector<int>& graph;
  int graph_k;
  const std::vector<int>& labels;
  double max_sq;
};

/// Union-find over segments.
class Groups
{
public:
  explicit Groups(std::size_t n) : parent_(n)
  {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int
  find(int s)
  {
    while (parent_[static_cast<std::size_t>(s)] != s) {
      const int up = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(s)])];
      parent_[static_cast<std::size_t>(s)] = up;
      s = up;
    }
    return s;
  }
  void
  unite(int a, int b)
  {
    const int ra = find(a), rb = find(b);
    if (ra != rb)
      parent_[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
  }

private:
  std::vector<int> parent_;
};

}  // namespace detail
}  // namespace segmentation
}  // namespace pcl_ls3d
