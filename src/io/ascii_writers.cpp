/// \file ascii_writers.cpp
/// \brief Shortest round-trip number text; ASCII PCD and PLY writers (see ascii_writers.h).

#include "ascii_writers.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <string>

#include <unistd.h>

namespace pcl_ls3d {
namespace io {
namespace detail {

void
appendNumber(std::string& out, double v, int decimals)
{
  char buffer[64];
  const auto r = decimals < 0 ? std::to_chars(buffer, buffer + sizeof(buffer), v)
                              : std::to_chars(buffer, buffer + sizeof(buffer), v, std::chars_format::fixed,
                                              std::min(decimals, 17));
  out.append(buffer, r.ec == std::errc() ? r.ptr : buffer);
}

void
appendNumber(std::string& out, float v)
{
  char buffer[64];
  const auto r = std::to_chars(buffer, buffer + sizeof(buffer), v);
  out.append(buffer, r.ec == std::errc() ? r.ptr : buffer);
}

namespace {

/// "x y z intensity gps_time point_source_id classification return_number number_of_returns\n"
void
appendPoint(std::string& line, const PointLiDAR& p, const Eigen::Vector3d& origin)
{
  const bool shifted = !origin.isZero(0.0);
  for (int k = 0; k < 3; ++k) {
    if (shifted)
      appendNumber(line, static_cast<double>(p.data[k]) + origin[k]);  // restored in double
    else
      appendNumber(line, p.data[k]);
    line += ' ';
  }
  appendNumber(line, p.intensity);
  line += ' ';
  appendNumber(line, p.gps_time);
  line += ' ' + std::to_string(p.point_source_id) + ' ' + std::to_string(p.classification) + ' ' +
          std::to_string(p.return_number) + ' ' + std::to_string(p.number_of_returns) + '\n';
}

bool
writeText(const std::string& path, const std::string& header, const pcl::PointCloud<PointLiDAR>& cloud,
          const Eigen::Vector3d& origin)
{
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f)
    return false;
  bool ok = std::fputs(header.c_str(), f) >= 0;
  std::string line;
  for (std::size_t i = 0; ok && i < cloud.size(); ++i) {
    line.clear();
    appendPoint(line, cloud[i], origin);
    ok = std::fwrite(line.data(), 1, line.size(), f) == line.size();
  }
  return (std::fclose(f) == 0) && ok;
}

}  // namespace

bool
writePcdAscii(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud,
              const Eigen::Vector3d& origin, const std::string& comments)
{
  const std::string xyz = origin.isZero(0.0) ? "4" : "8", n = std::to_string(cloud.size());
  const std::string header = "# .PCD v0.7 - Point Cloud Data file format\n" + comments +
                             "VERSION 0.7\n"
                             "FIELDS x y z intensity gps_time point_source_id classification return_number "
                             "number_of_returns\nSIZE " +
                             xyz + " " + xyz + " " + xyz +
                             " 4 8 2 1 1 1\n"
                             "TYPE F F F F F U U U U\nCOUNT 1 1 1 1 1 1 1 1 1\nWIDTH " +
                             n +
                             "\nHEIGHT 1\n"
                             "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
                             n + "\nDATA ascii\n";
  return writeText(path, header, cloud, origin);
}

bool
writePlyAscii(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud,
              const Eigen::Vector3d& origin, const std::string& comments)
{
  const std::string t = origin.isZero(0.0) ? "float" : "double";
  const std::string header =
      "ply\nformat ascii 1.0\n" + comments + "comment pcl_ls3d\nelement vertex " +
      std::to_string(cloud.size()) + "\nproperty " + t + " x\nproperty " + t + " y\nproperty " + t +
      " z\n"
      "property float intensity\nproperty double gps_time\nproperty ushort point_source_id\n"
      "property uchar classification\nproperty uchar return_number\n"
      "property uchar number_of_returns\nend_header\n";
  return writeText(path, header, cloud, origin);
}

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d

namespace pcl_ls3d {
namespace io {
namespace detail {

bool
insertPlyComments(const std::string& path, const std::string& comments)
{
  if (comments.empty())
    return true;
  // Beside the output (same file system, so the rename is atomic), unique to this process.
  const std::string temporary = path + ".pcl_ls3d_tmp" + std::to_string(::getpid());
  bool ok = false;
  {
    std::ifstream in(path, std::ios::binary);
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    std::string line;
    while (!ok && std::getline(in, line)) {  // "ply", then "format ..."
      out << line << '\n';
      if (line.compare(0, 7, "format ") == 0) {
        out << comments << in.rdbuf();  // the rest of the header and the data, as PCL wrote them
        ok = true;
      }
    }
    ok = ok && out.flush();
  }
  ok = ok && std::rename(temporary.c_str(), path.c_str()) == 0;
  if (!ok) {  // no output without its CRS line, no temporary left behind
    std::remove(temporary.c_str());
    std::remove(path.c_str());
  }
  return ok;
}

}  // namespace detail
}  // namespace io
}  // namespace pcl_ls3d
