/// \file test_reader_memory.cpp
/// \brief Issue 12: a memory bound per reader. A header that claims far more points than the file
///        holds (LAS 2^32 - 1, PCD 10^9 in each encoding, PLY 2^32 - 1) and a 10 MB XYZ line of
///        garbage must fail with small memory: each load runs in a forked child whose peak
///        resident set is measured and whose address space is capped (memory_probe.h).

#include <pcl_ls3d/io/cloud_io.h>

#include "io/hostile_files.h"
#include "io/io_test_utils.h"
#include "io/memory_probe.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iostream>

using pcl_ls3d_test::probeLoad;
using pcl_ls3d_test::TempDir;

namespace {

constexpr long kCapMb = 512;        // address-space headroom of the child (outside ASan)
constexpr long kHostileKb = 32768;  // a refused 10-point file may cost at most 32 MiB

void
expectSmallRefusal(const std::string& path, const std::string& expect, long max_kb)
{
  SCOPED_TRACE(path);
  const auto r = probeLoad(path, kCapMb);
  ASSERT_TRUE(r.child_ok) << "the load crashed or hit the allocation cap";
  std::cout << path << ": refused with peak RSS growth " << r.peak_growth_kb << " KiB\n";
  EXPECT_FALSE(r.loaded);
  EXPECT_NE(r.error.find(expect), std::string::npos) << r.error;
  EXPECT_LT(r.peak_growth_kb, max_kb) << "peak RSS growth " << r.peak_growth_kb << " KiB";
}

}  // namespace

// The probe sees real allocations: a legitimate 1-million-point binary PCD (12 MB) loads and
// costs more than 40 MiB (the cloud alone is 48 bytes per point), below the cap.
TEST(ReaderMemory, ProbeMeasuresARealLoad)
{
  TempDir dir("ls3d_mem_ok");
  const int n = 1000000;
  std::ofstream(dir.file("big.pcd"), std::ios::binary)
      << pcl_ls3d_test::pcdHeader(std::to_string(n), std::to_string(n), "binary")
      << pcl_ls3d_test::floatTriplets(n);
  const auto r = probeLoad(dir.file("big.pcd"), kCapMb);
  ASSERT_TRUE(r.child_ok);
  std::cout << "1 M points loaded with peak RSS growth " << r.peak_growth_kb << " KiB\n";
  EXPECT_TRUE(r.loaded) << r.error;
  EXPECT_GT(r.peak_growth_kb, 40 * 1024);
}

TEST(ReaderMemory, LasCountBeyondTheFile)
{
  const std::string corpus = std::string(PCL_LS3D_TEST_SOURCE_DIR) + "/data/las_corpus/";
  expectSmallRefusal(corpus + "count_huge.las", "4294967295", kHostileKb);
  expectSmallRefusal(corpus + "count64_huge.las", "point", kHostileKb);
}

TEST(ReaderMemory, PcdPlyCountsBeyondTheFile)
{
  TempDir dir("ls3d_mem_hostile");
  for (const auto& f : pcl_ls3d_test::hostileFiles()) {
    std::ofstream(dir.file(f.name), std::ios::binary) << f.bytes;
    expectSmallRefusal(dir.file(f.name), f.expect, kHostileKb);
  }
}

// 10 MB of garbage on one line: the reader holds the line once; the error is short.
TEST(ReaderMemory, XyzGarbageLine)
{
  TempDir dir("ls3d_mem_xyz");
  std::ofstream(dir.file("garbage.xyz"), std::ios::binary) << std::string(10000000, 'q') << "\n";
  expectSmallRefusal(dir.file("garbage.xyz"), "(10000000 characters)", 4 * 10000 + kHostileKb);
}
