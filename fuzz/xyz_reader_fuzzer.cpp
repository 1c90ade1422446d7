/// \file xyz_reader_fuzzer.cpp
/// \brief libFuzzer target: pcl_ls3d::io::readXyz on arbitrary text must return true or false
///        (fuzz_checks.h). The first byte picks a column list (none, or one of three), so the
///        mapping by option is fuzzed as well as the mapping by header line and position.

#include <pcl_ls3d/io/xyz_io.h>

#include "fuzz_checks.h"

#include <sstream>

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
    return 0;
  static const char* const kColumns[] = {"", "x,y,z,intensity,classification", "_,x,y,z",
                                         "z,y,x,gps_time,point_source_id,return_number,"
                                         "number_of_returns"};
  pcl_ls3d::io::LoadOptions options;
  options.xyz_columns = kColumns[data[0] % 4];
  std::istringstream in(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
  pcl_ls3d::io::CloudInfo info;
  std::string error;
  const bool ok = pcl_ls3d::io::readXyz(in, cloud, info, error, options);
  pcl_ls3d_fuzz::checkResult(ok, error, cloud, info);
  return 0;
}
