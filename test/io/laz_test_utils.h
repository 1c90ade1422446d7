#pragma once
/// \file laz_test_utils.h
/// \brief Helpers of the LAZ tests: the shared data folder, whole files as bytes, and the point
///        records of a LAS or LAZ file (a LAZ file's through decompressLaz()).

#include <pcl_ls3d/io/las_io.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace pcl_ls3d_test {

inline std::string
sharedData(const std::string& relative)
{
  return std::string(PCL_LS3D_SHARED_DATA_DIR) + "/" + relative;
}

/// GTEST_SKIP()s the calling test when the file is absent (the shared data is optional).
#define PCL_LS3D_REQUIRE_DATA(path)                                                                          \
  if (!std::filesystem::exists(path))                                                                        \
  GTEST_SKIP() << "shared data not found: " << (path)

inline std::vector<std::uint8_t>
readBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

inline void
writeBytes(const std::string& path, const std::vector<std::uint8_t>& bytes)
{
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

/// The point records (record_length · count bytes) of an in-memory LAS file.
inline std::vector<std::uint8_t>
lasRecords(const std::vector<std::uint8_t>& las, pcl_ls3d::io::LasHeaderInfo& h)
{
  std::string error;
  EXPECT_TRUE(pcl_ls3d::io::readLasHeader(las.data(), las.size(), h, error)) << error;
  if (h.laz.compressed)
    return {};
  const std::size_t bytes = static_cast<std::size_t>(h.point_count) * h.record_length;
  return std::vector<std::uint8_t>(las.begin() + h.offset_to_points,
                                   las.begin() + h.offset_to_points + bytes);
}

/// The point records of a LAZ file, decoded; empty (with a test failure) when it does not decode.
inline std::vector<std::uint8_t>
lazRecords(const std::vector<std::uint8_t>& laz, pcl_ls3d::io::LasHeaderInfo& h)
{
  std::vector<std::uint8_t> las;
  std::string error;
  EXPECT_TRUE(pcl_ls3d::io::decompressLaz(laz.data(), laz.size(), las, error)) << error;
  return las.empty() ? las : lasRecords(las, h);
}

}  // namespace pcl_ls3d_test
