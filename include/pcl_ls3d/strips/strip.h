#pragma once
/// \file strip.h
/// \brief One flight strip as the strip adjustment sees it: its points in local coordinates
///        about the strip's own origin (float is ample: 0.1 mm at 2 km), the ASPRS class of each
///        point and whether the point may be observed at all.
///
/// Frames. File coordinates (e.g. Lambert-93, double) = block origin O + block coordinates;
/// block coordinates of a strip point = strip origin o_k + its local coordinates. Strip k's
/// correction acts about o_k: x_corrected = o_k + t + m R (x_local) (Zuo et al. 2012, eq. 2,
/// reduced), which keeps rotations and translations apart on georeferenced data.

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace strips {

/// \brief Why points are left out of the observations (they are still corrected and written).
struct ExclusionCounts
{
  std::size_t psid_zero = 0;   ///< point-source id 0 (no flight line)
  std::size_t withheld = 0;    ///< LAS withheld flag
  std::size_t synthetic = 0;   ///< LAS synthetic flag
  std::size_t non_finite = 0;  ///< NaN / inf coordinates (dropped by the readers)
};

/// \brief A strip's points and attributes.
struct Strip
{
  std::string name;                                  ///< "psid706", or the input file's stem
  int point_source_id = -1;                          ///< the LAS point-source id when split by it
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< o_k in block coordinates
  std::vector<Eigen::Vector3f> points;               ///< local coordinates (block − o_k)
  std::vector<std::uint8_t> classification;          ///< ASPRS class per point (0 when unknown)
  std::vector<std::uint8_t> observable;              ///< 1: may be observed; 0: excluded (see counts)
  ExclusionCounts excluded;

  std::size_t
  size() const
  {
    return points.size();
  }
  /// Block coordinates of point i.
  Eigen::Vector3d
  blockPoint(std::size_t i) const
  {
    return origin + points[i].cast<double>();
  }
  /// Number of observable points.
  std::size_t
  observableCount() const;
  /// True when more than half of the observable points carry a class other than 0 (never
  /// classified) and 1 (unclassified): then the class filter selects stable surfaces.
  bool
  classified() const;
};

/// \brief Builds a strip from block coordinates: chooses o_k (the centre of the points' XY
///        bounding box, rounded to whole units, and their mean height) and stores local
///        coordinates. `classification` and `observable` may be empty (0 and 1 for all).
Strip
makeStrip(std::string name, int point_source_id, const std::vector<Eigen::Vector3d>& block_points,
          std::vector<std::uint8_t> classification = {}, std::vector<std::uint8_t> observable = {});

}  // namespace strips
}  // namespace pcl_ls3d
