#pragma once
/// \file tool_output.h
/// \brief Console output shared by the pcl_ls3d_* tools.

#include <pcl_ls3d/io/cloud_pair.h>
#include <pcl_ls3d/io/json_text.h>

#include <pcl/console/print.h>

#include <Eigen/Core>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

namespace pcl_ls3d {
namespace tools {

/// \brief Line-buffered stdout, so that a log holding stdout and stderr (2>&1 into a file) keeps
///        each error and warning next to the progress line it belongs to: the first call of
///        every tool's main.
inline void
lineBufferedStdout()
{
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
}

/// \brief A finite number as JSON, or null (JSON has no NaN or infinity).
inline nlohmann::json
finiteOrNull(double v)
{
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

/// \brief Writes a JSON report (io::toJsonText, indent 2, a final newline); false when it could
///        not be written.
template <typename Json>
inline bool
writeJsonFile(const std::string& path, const Json& json)
{
  std::ofstream out(path);
  return static_cast<bool>(out << io::toJsonText(json, 2) << "\n");
}

/// \brief What loading a pair found (io::loadCloudPair): one warning line per CRS that differs,
///        then one line per file whose heights were converted to the plan unit.
inline void
printPairNotes(const io::CloudPair& pair)
{
  for (const std::string& warning : pair.warnings)
    pcl::console::print_warn("Warning: %s\n", warning.c_str());
  for (const std::string& note : pair.notes)
    pcl::console::print_info("%s\n", note.c_str());
}

/// \brief Prints a 4x4 transformation of input coordinates under `title`. The coordinates may be
///        projected (10^6 m): the rotation needs 15 decimals for its product with them to hold
///        to 1e-8 m, so that the printed matrix can be copied into another program.
inline void
printTransformation(const char* title, const Eigen::Matrix4d& T)
{
  pcl::console::print_info("%s\n", title);
  for (int i = 0; i < 4; ++i)
    pcl::console::print_info("  %18.15f %18.15f %18.15f %21.9f\n", T(i, 0), T(i, 1), T(i, 2), T(i, 3));
}

}  // namespace tools
}  // namespace pcl_ls3d
