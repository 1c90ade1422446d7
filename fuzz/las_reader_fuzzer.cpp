/// \file las_reader_fuzzer.cpp
/// \brief libFuzzer target: pcl_ls3d::io::readLas on arbitrary bytes must return true or false
///        (fuzz_checks.h), never crash, over-read or allocate more than the input justifies. When
///        a buffer parses, the cloud is written back and re-read (writer coverage, and a
///        consistency check).

#include <pcl_ls3d/io/las_io.h>

#include "fuzz_checks.h"

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
  pcl_ls3d::io::CloudInfo info;
  std::string error;
  pcl_ls3d::io::LoadOptions load;
  load.allow_empty = true;
  const bool ok = pcl_ls3d::io::readLas(data, size, cloud, info, error, load);
  pcl_ls3d_fuzz::checkResult(ok, error, cloud, info);
  if (!ok)
    return 0;
  if (cloud.size() != info.las.point_count)
    std::abort();
  pcl_ls3d::io::SaveOptions save;
  save.las_point_format = info.las.point_format;
  save.las_minor_version =
      info.las.version_minor < 4 && info.las.point_format >= 6 ? 4 : info.las.version_minor;
  save.las_scale = info.las.scale.cwiseAbs();
  save.las_vlrs = info.las.vlrs;
  std::vector<std::uint8_t> bytes;
  if (!pcl_ls3d::io::writeLas(cloud, info.origin, bytes, error, save))
    return 0;  // legitimately refused (e.g. a version too old for the format)
  pcl::PointCloud<pcl_ls3d::PointLiDAR> again;
  pcl_ls3d::io::CloudInfo info2;
  if (!pcl_ls3d::io::readLas(bytes.data(), bytes.size(), again, info2, error, load) ||
      again.size() != cloud.size())
    std::abort();  // what we write we must read
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (again[i].classification != cloud[i].classification ||
        again[i].point_source_id != cloud[i].point_source_id)
      std::abort();
  return 0;
}
