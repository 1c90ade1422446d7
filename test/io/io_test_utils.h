#pragma once
/// \file io_test_utils.h
/// \brief Helpers shared by the IO tests: synthetic georeferenced clouds and temp folders.

#include <pcl_ls3d/point_types.h>

#include <pcl/point_cloud.h>

#include <Eigen/Core>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace pcl_ls3d_test {

/// A cloud at UTM scale: file coordinates are whole millimetres around `base` (so a LAS writer at
/// 1 mm quantum is exact), stored local to `origin`. Attributes are random but valid for `format`.
inline void
makeUtmCloud(std::size_t n, int format, const Eigen::Vector3d& base, const Eigen::Vector3d& origin,
             pcl::PointCloud<pcl_ls3d::PointLiDAR>& cloud, std::vector<Eigen::Vector3d>& file_xyz,
             unsigned seed = 42)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> mm(-400000, 400000);  // +-400 m in mm
  const bool new_layout = format >= 6;
  const bool has_time = format == 1 || format >= 3;
  cloud.clear();
  file_xyz.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d x = base + Eigen::Vector3d(mm(rng), mm(rng), mm(rng) / 20) * 1e-3;
    pcl_ls3d::PointLiDAR p;
    p.x = static_cast<float>(x[0] - origin[0]);
    p.y = static_cast<float>(x[1] - origin[1]);
    p.z = static_cast<float>(x[2] - origin[2]);
    p.intensity = static_cast<float>(rng() % 65536);
    p.classification = static_cast<std::uint8_t>(rng() % (new_layout ? 256 : 32));
    p.point_source_id = static_cast<std::uint16_t>(rng() % 65536);
    const unsigned max_ret = new_layout ? 15 : 7;
    p.number_of_returns = static_cast<std::uint8_t>(1 + rng() % max_ret);
    p.return_number = static_cast<std::uint8_t>(1 + rng() % p.number_of_returns);
    p.gps_time = has_time ? 3.0e8 + static_cast<double>(rng() % 1000000) * 1e-6 * 997.0 : 0.0;
    cloud.push_back(p);
    file_xyz.push_back(x);
  }
}

/// A fresh empty folder under the system temp dir, removed at destruction.
struct TempDir
{
  std::filesystem::path path;
  explicit TempDir(const std::string& name)
  {
    path = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(std::random_device{}()));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir()
  {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string
  file(const std::string& name) const
  {
    return (path / name).string();
  }
};

}  // namespace pcl_ls3d_test
