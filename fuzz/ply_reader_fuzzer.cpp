/// \file ply_reader_fuzzer.cpp
/// \brief libFuzzer target: pcl_ls3d::io::readPly on arbitrary bytes must return true or false
///        (fuzz_checks.h), never crash, over-read or allocate more than the input justifies.

#include <pcl_ls3d/io/ply_io.h>

#include "fuzz_checks.h"

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
  pcl_ls3d::io::CloudInfo info;
  std::string error;
  const bool ok = pcl_ls3d::io::readPly(data, size, cloud, info, error);
  pcl_ls3d_fuzz::checkResult(ok, error, cloud, info);
  return 0;
}
