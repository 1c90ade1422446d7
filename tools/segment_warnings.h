#pragma once
/// \file segment_warnings.h
/// \brief What pcl_ls3d_segment says about its input before it runs (far outliers, data too
///        sparse for whole objects) and about a result that found no structure.

#include <pcl_ls3d/common/voxel_index.h>
#include <pcl_ls3d/segmentation/object_classes.h>
#include <pcl_ls3d/stats/descriptive.h>

#include <pcl/PointIndices.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace tools {

/// Points far outside the data's dense core (a stray return kilometres away) stretch the
/// extent that the ground grid and the origin are taken from and change the segmentation: said,
/// not hidden. "" when the extent is within 4 × that of the central 99.8 % of the points.
inline std::string
farOutlierWarning(const pcl::PointCloud<pcl::PointXYZ>& cloud)
{
  if (cloud.size() < 1000)
    return "";
  double core = 0.0, full = 0.0;
  for (int axis = 0; axis < 2; ++axis) {
    std::vector<double> v;
    v.reserve(cloud.size());
    for (const auto& p : cloud)
      v.push_back(axis == 0 ? p.x : p.y);
    const std::vector<double> q = stats::quantiles(std::move(v), {0.0, 0.001, 0.999, 1.0});
    core = std::max(core, q[2] - q[1]);
    full = std::max(full, q[3] - q[0]);
  }
  if (!(full > 4.0 * core))
    return "";
  char buf[240];
  std::snprintf(buf, sizeof(buf),
                "the points span %.0f m, but 99.8 %% of them lie within %.0f m: far outliers change the "
                "grid and the segmentation; crop them first",
                full, core);
  return buf;
}

/// Below about 2 points per m² a house or a crown is a handful of points, and the growth radius
/// (2 k_min-th neighbour distances, about 4 mean spacings 1/√density) spans the gaps between
/// them: objects join. Measured on IGN tiles thinned at
/// random (docs/BENCHMARKS.md, "Sparse data"): said before the run, not discovered in the maps.
inline std::string
sparseDataWarning(const pcl::PointCloud<pcl::PointXYZ>& cloud)
{
  // Density over the 5 m cells that hold points (metres): gaps (water, a cropped corner) do not
  // count.
  std::vector<Eigen::Vector3d> points;
  points.reserve(cloud.size());
  for (const auto& p : cloud)
    points.emplace_back(p.x, p.y, p.z);
  const double cell_m = 5.0;
  const auto occupied = static_cast<double>(occupiedCells(points, 0, 1, cell_m));
  const double density = static_cast<double>(cloud.size()) / (occupied * cell_m * cell_m);
  if (!(occupied > 0.0) || density >= 2.0)
    return "";
  const double spacing = 1.0 / std::sqrt(density);
  char buf[400];
  std::snprintf(buf, sizeof(buf),
                "%.3g points per m² (mean spacing %.2f m): too sparse for whole objects; houses, "
                "crowns and the ground closer than about 4 spacings join (on an IGN tile thinned "
                "to 1.5 points per m², vegetation F1 fell from 0.89 to 0.34); object "
                "segmentation wants at least 2-4 points per m²",
                density, spacing);
  return buf;
}

/// One unclassified object holding nearly every point means the segmentation found no structure
/// (IGN's La Réunion sample, a wooded ravine: one segment of 99.5 %): said, so that nobody takes
/// that one segment for a result. "" otherwise (also without classes; a tile that is all
/// ground, all wood or one roof is a result).
inline std::string
dominantSegmentWarning(const std::vector<pcl::PointIndices>& segments,
                       const std::vector<segmentation::ObjectClass>& classes, std::size_t points)
{
  if (points < 1000 || classes.size() != segments.size())
    return "";
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const double share = static_cast<double>(segments[s].indices.size()) / static_cast<double>(points);
    if (share > 0.9 && classes[s] == segmentation::ObjectClass::Unclassified) {
      char buf[300];
      std::snprintf(buf, sizeof(buf),
                    "one unclassified segment holds %.1f %% of the points: no structure was found "
                    "(steep or densely wooded terrain, or too few points per object)",
                    100.0 * share);
      return buf;
    }
  }
  return "";
}

}  // namespace tools
}  // namespace pcl_ls3d
