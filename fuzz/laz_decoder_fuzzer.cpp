/// \file laz_decoder_fuzzer.cpp
/// \brief libFuzzer target for the LAZ decoder: arbitrary bytes go through readLas() (the chunk
///        container, the chunk table and every item coder, into a cloud) and decompressLaz()
///        (the same into LAS records). Both must return true or false with one short line, never
///        crash, over-read or allocate beyond what the input justifies. A file that decodes is
///        compressed again (chunks of 1-64 points, or more in large files, so chunk boundaries are
///        exercised) and must
///        decode to exactly the same LAS bytes: what we write we must read, record for record.

#include <pcl_ls3d/io/las_io.h>

#include "fuzz_checks.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

void
checkReason(const std::string& error)
{
  if (error.empty() || error.size() > 400 || error.find('\n') != std::string::npos) {
    std::fprintf(stderr, "fuzz check failed: a failure must say why in one short line: %s\n",
                 error.substr(0, 300).c_str());
    std::abort();
  }
}

}  // namespace

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
  pcl_ls3d::io::CloudInfo info;
  std::string error;
  pcl_ls3d::io::LoadOptions load;
  load.allow_empty = true;
  const bool loaded = pcl_ls3d::io::readLas(data, size, cloud, info, error, load);
  pcl_ls3d_fuzz::checkResult(loaded, error, cloud, info);
  if (loaded && cloud.size() != info.las.point_count)
    std::abort();

  std::vector<std::uint8_t> las;
  if (!pcl_ls3d::io::decompressLaz(data, size, las, error)) {
    checkReason(error);
    return 0;
  }
  pcl_ls3d::io::LasHeaderInfo h;
  if (!pcl_ls3d::io::readLasHeader(las.data(), las.size(), h, error) || h.laz.compressed)
    std::abort();  // a decompressed file is plain LAS
  if (loaded && h.point_count != cloud.size())
    std::abort();  // both paths decode the same records

  // 1-64 points a chunk as the last byte says, but no more than about 64 chunks: every chunk
  // resets the models, which under the sanitizers costs milliseconds.
  std::uint64_t chunk = 1u + (size > 0 ? data[size - 1] % 64u : 0u);
  chunk = std::max<std::uint64_t>(chunk, h.point_count / 64 + 1);
  std::vector<std::uint8_t> laz, back;
  if (!pcl_ls3d::io::compressLas(las.data(), las.size(), laz, error,
                                 static_cast<std::uint32_t>(std::min<std::uint64_t>(chunk, 0xFFFFFFFEu)))) {
    checkReason(error);  // e.g. a waveform format, which the writer refuses
    return 0;
  }
  if (!pcl_ls3d::io::decompressLaz(laz.data(), laz.size(), back, error) || back != las) {
    std::fprintf(stderr, "fuzz check failed: re-compressed file does not decode back: %s\n", error.c_str());
    std::abort();
  }
  return 0;
}
