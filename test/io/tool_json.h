#pragma once
// A tool's JSON report read back in the tests.
#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <fstream>
#include <string>

namespace pcl_ls3d_test {

inline nlohmann::json
readJson(const std::string& path)
{
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

/// A 4x4 matrix stored as four rows (the reports' "transformation").
inline Eigen::Matrix4d
jsonMatrix(const nlohmann::json& rows)
{
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      T(r, c) = rows.at(static_cast<std::size_t>(r)).at(static_cast<std::size_t>(c)).get<double>();
  return T;
}

}  // namespace pcl_ls3d_test
