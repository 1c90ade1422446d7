#pragma once
/// \file target_surface.h
/// \brief What a conjugate-point rule may ask of the target: its points and a nearest-neighbour
///        search. The registration wraps its PCL cloud and kd-tree in this, so rules (and the
///        adjustment core) need no PCL point type and users can write rules without templates.

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <vector>

namespace pcl_ls3d {

/// \brief Read-only access to the target surface samples (thread-safe for concurrent queries).
class TargetSurface
{
public:
  virtual ~TargetSurface() = default;

  /// Number of target points.
  virtual std::size_t
  size() const = 0;

  /// Coordinates of target point `index` (cloud coordinates, double).
  virtual Eigen::Vector3d
  point(int index) const = 0;

  /// The k nearest target points of `query`, closest first; squared distances in `sq_dists`.
  /// Returns the number found (0 on failure). Must be callable from several threads at once.
  virtual int
  nearestKSearch(const Eigen::Vector3d& query, int k, std::vector<int>& indices,
                 std::vector<float>& sq_dists) const = 0;
};

/// \brief A TargetSurface over plain coordinates with a brute-force search (tests, tiny inputs).
class PointVectorTargetSurface : public TargetSurface
{
public:
  explicit PointVectorTargetSurface(std::vector<Eigen::Vector3d> points) : points_(std::move(points))
  {}
  std::size_t
  size() const override
  {
    return points_.size();
  }
  Eigen::Vector3d
  point(int index) const override
  {
    return points_[static_cast<std::size_t>(index)];
  }
  int
  nearestKSearch(const Eigen::Vector3d& query, int k, std::vector<int>& indices,
                 std::vector<float>& sq_dists) const override;

private:
  std::vector<Eigen::Vector3d> points_;
};

}  // namespace pcl_ls3d
