#pragma once
/// \file fuzz_checks.h
/// \brief What every reader fuzzer asserts about one result: a failure carries a short one-line
///        reason; a success is dense, finite and counted consistently (a region query's points
///        left out counted too).

#include <pcl_ls3d/io/cloud_io.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace pcl_ls3d_fuzz {

inline void
checkResult(bool ok, const std::string& error, const pcl::PointCloud<pcl_ls3d::PointLiDAR>& cloud,
            const pcl_ls3d::io::CloudInfo& info, std::size_t max_error = 400)
{
  const auto fail = [](const char* why, const std::string& detail) {
    std::fprintf(stderr, "fuzz check failed: %s %s\n", why, detail.substr(0, 300).c_str());
    std::abort();
  };
  if (!ok) {
    if (error.empty() || error.size() > max_error || error.find('\n') != std::string::npos)
      fail("a failure must say why, in one short line:", error);
    return;
  }
  if (cloud.size() != info.points_loaded ||
      info.points_loaded + info.points_dropped_nonfinite + info.points_outside_region !=
          info.points_in_file ||
      !cloud.is_dense || (!cloud.empty() && cloud.height != 1))
    fail("inconsistent counts", std::to_string(cloud.size()) + " " + std::to_string(info.points_loaded) +
                                    " " + std::to_string(info.points_dropped_nonfinite) + " " +
                                    std::to_string(info.points_in_file));
  if (!info.origin.allFinite())
    fail("origin not finite", "");
  for (const auto& p : cloud)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail("a loaded point is not finite:",
           std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z));
}

}  // namespace pcl_ls3d_fuzz
