#pragma once
// Smooth analytic terrain sampled into point sets, and a kd-tree TargetSurface over them: the
// inputs of the engine-stage tests (pair matcher, block adjustment).
#include <pcl_ls3d/registration/pcl_target_surface.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

namespace engine_test {

/// z = f(x, y): gentle relief with two wavelengths and a slope (every parameter determinable).
inline double
terrain(double x, double y)
{
  return 3.0 * std::sin(x / 15.0) * std::cos(y / 11.0) + 1.5 * std::sin((x + 2.0 * y) / 23.0) + 0.05 * x;
}

/// Jittered grid samples of the terrain over [x0, x1] × [y0, y1], spacing `step`, isotropic
/// noise `sigma`.
inline std::vector<Eigen::Vector3d>
sampleTerrain(double x0, double x1, double y0, double y1, double step, double sigma, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3 * step, 0.3 * step);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<Eigen::Vector3d> points;
  for (double y = y0; y <= y1; y += step)
    for (double x = x0; x <= x1; x += step) {
      const double px = x + jitter(rng), py = y + jitter(rng);
      points.emplace_back(px + noise(rng), py + noise(rng), terrain(px, py) + noise(rng));
    }
  return points;
}

/// A kd-tree TargetSurface over points (kept alive by the object).
class KdSurface
{
public:
  explicit KdSurface(const std::vector<Eigen::Vector3d>& points)
      : cloud_(new pcl::PointCloud<pcl::PointXYZ>), tree_(new pcl::search::KdTree<pcl::PointXYZ>)
  {
    for (const auto& p : points)
      cloud_->push_back(
          pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())));
    tree_->setInputCloud(cloud_);
    surface_ = std::make_unique<pcl_ls3d::PclTargetSurface<pcl::PointXYZ>>(cloud_, tree_);
  }
  const pcl::search::KdTree<pcl::PointXYZ>&
  tree() const
  {
    return *tree_;
  }

  const pcl_ls3d::TargetSurface&
  surface() const
  {
    return *surface_;
  }

private:
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud_;
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree_;
  std::unique_ptr<pcl_ls3d::PclTargetSurface<pcl::PointXYZ>> surface_;
};

/// p − origin for every point.
inline std::vector<Eigen::Vector3d>
reduce(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin)
{
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (const auto& p : points)
    out.push_back(p - origin);
  return out;
}

}  // namespace engine_test
