#pragma once
/// \file reference_objects.h
/// \brief Reference objects for the object-based evaluation of Wang et al. 2021 §4.1: whole
///        objects (a building, a tree group, a ground piece, a wire span), either derived from a
///        classification as connected components per class group, or given by a generator's
///        object ids.

#include <pcl_ls3d/evaluation/segmentation_classes.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstddef>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// \brief Objects of a cloud: one id per point and a class group per object.
struct ReferenceObjects
{
  static constexpr int kUnlabelled = -1;  ///< excluded code: neither object nor "other"
  /// Per point: object id (0..objects−1) or kUnlabelled.
  std::vector<int> object_of;
  /// Per object: index into the class groups, or ClassLookup::kOther (evaluated code in no
  /// group: such objects make segments impure but are not scored).
  std::vector<int> group_of_object;
  std::vector<std::size_t> size;         ///< points per object
  std::vector<std::string> group_names;  ///< names of the class groups, in order
  double radius = 0.0;                   ///< connectivity radius used (0 for objects given by ids)

  std::size_t
  objects() const
  {
    return size.size();
  }
};

/// \brief How objects are derived from a classification.
struct ReferenceObjectSettings
{
  std::vector<ClassGroup> groups = defaultClassGroups();
  std::vector<int> excluded_codes = defaultExcludedCodes();
  /// Connectivity radius [cloud units]: points of one class group closer than this are in the
  /// same object. ≤ 0: automatic, max(1, 2.5 × median nearest-neighbour distance) — 1 m on
  /// airborne tiles of ≥ 2 points/m² (the "1 m Euclidean clusters"), wider on sparse
  /// tiles so that a building of 0.3 points/m² is not cut into single points.
  double radius = -1.0;
  /// Groups connected in plan (x, y only): a building is one object over its whole footprint.
  /// Airborne scans hold few wall points, so in 3-D a roof step or a facade a storey below the
  /// eaves is more than the radius away from the roof above it and would be a separate object.
  std::vector<std::string> plan_connected_groups{"building"};
};

/// \brief Connected components per class group (Euclidean clusters of the given radius, in plan
///        for plan_connected_groups): each group's points (codes of "other" form their own
///        components too) become objects.
/// \return false with a one-line reason (sizes differ, empty cloud)
bool
referenceObjectsFromLabels(const pcl::PointCloud<pcl::PointXYZ>& cloud, const std::vector<int>& labels,
                           const ReferenceObjectSettings& settings, ReferenceObjects& objects,
                           std::string& error);

/// \brief Objects given by ids (generator): ids ≥ 0 are objects (renumbered densely in order
///        of first appearance), id < 0 or an excluded code makes a point unlabelled. Each
///        object's group is the majority group of its points' labels.
/// \return false with a one-line reason (sizes differ)
bool
referenceObjectsFromIds(const std::vector<int>& ids, const std::vector<int>& labels,
                        const std::vector<ClassGroup>& groups, const std::vector<int>& excluded_codes,
                        ReferenceObjects& objects, std::string& error);

}  // namespace evaluation
}  // namespace pcl_ls3d
