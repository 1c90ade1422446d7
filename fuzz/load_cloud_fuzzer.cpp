/// \file load_cloud_fuzzer.cpp
/// \brief libFuzzer target for the dispatcher: the input (after its first byte) is written to a
///        file whose extension the first byte picks (.las .pcd .ply .xyz .txt .csv .dat .laz), so
///        loadCloud()'s existence/size/LAZ checks, signature sniffing and every reader run as a
///        tool would run them. A cloud that loads is written back by saveCloud() in a format the
///        first byte's upper bits pick and must load again with the same number of points
///        ("what we write we read"), unless the writer refuses it with a reason.

#include <pcl_ls3d/io/cloud_io.h>

#include "fuzz_checks.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace {

std::filesystem::path
workDir()
{
  static const std::filesystem::path dir = [] {
    const std::filesystem::path base =
        std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
    const auto d = base / ("pcl_ls3d_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
    return 0;
  static const char* const kIn[] = {"las", "pcd", "ply", "xyz", "txt", "csv", "dat", "laz"};
  static const char* const kOut[] = {"pcd", "ply", "las", "xyz"};
  const std::string input = (workDir() / (std::string("in.") + kIn[data[0] % 8])).string();
  {
    std::ofstream f(input, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data) + 1, static_cast<std::streamsize>(size - 1));
  }
  pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
  pcl_ls3d::io::CloudInfo info;
  std::string error;
  const bool ok = pcl_ls3d::io::loadCloud(input, cloud, info, error);
  pcl_ls3d_fuzz::checkResult(ok, error, cloud, info, 400 + input.size());
  std::filesystem::remove(input);
  if (!ok)
    return 0;

  const std::string output = (workDir() / (std::string("out.") + kOut[(data[0] >> 3) % 4])).string();
  pcl_ls3d::io::SaveOptions save;
  save.overwrite = true;
  save.binary = (data[0] >> 5) % 2 == 0;
  if (!pcl_ls3d::io::saveCloud(output, cloud, info.origin, error, save)) {
    if (error.empty())
      std::abort();
    return 0;
  }
  pcl::PointCloud<pcl_ls3d::PointLiDAR> again;
  pcl_ls3d::io::LoadOptions load;
  load.use_origin = true;
  load.origin = info.origin;
  if (!pcl_ls3d::io::loadCloud(output, again, info, error, load) || again.size() != cloud.size())
    std::abort();  // what we write we must read
  std::filesystem::remove(output);
  return 0;
}
