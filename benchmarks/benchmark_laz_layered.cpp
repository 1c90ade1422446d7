// benchmark_laz_layered: single-thread throughput of the layered LAZ chunk coders (point
// formats 6–10) on real files, chunk after chunk as a reader and a writer would run them.
//
//   benchmark_laz_layered [FILE.laz ...] [-reps N]
//       Default files: the PF6 and PF8 IGN tiles of shared/data/laz/ign. Per file: points,
//       compressed bytes per point, compression ratio against the LAS records, and the best of
//       N runs (default 5) of decoding and of encoding every chunk, in million points per
//       second of CPU time and of wall time. Encoding needs fixed-size chunks (not COPC).
//
// Until the LAZ container lands this walks the chunks with the test-side walker
// (test/io/laz_chunk_walker.h); the file is read into memory before timing.
#include "io/laz/laszip_items.h"
#include "io/laz_chunk_walker.h"

#include <pcl/console/parse.h>
#include <pcl/console/print.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

namespace laz = pcl_ls3d::io::laz;

namespace {

/// Best CPU and wall seconds of `reps` runs of `run`.
template <typename Run>
std::pair<double, double>
bestOf(int reps, Run run)
{
  double cpu = 1e30, wall = 1e30;
  for (int k = 0; k < reps; ++k) {
    const std::clock_t c0 = std::clock();
    const auto w0 = std::chrono::steady_clock::now();
    run();
    cpu = std::min(cpu, double(std::clock() - c0) / CLOCKS_PER_SEC);
    wall = std::min(wall, std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
  }
  return {cpu, wall};
}

/// Points of the chunk starting at `p`: the fixed chunk size (the last chunk partial) or, for
/// variable chunks, the count stored after the chunk's first record.
std::size_t
chunkPoints(const laz_test::LasFile& f, const laz::LaszipVlr& vlr, const std::uint8_t* p, std::uint64_t done)
{
  std::uint64_t n = vlr.chunk_size;
  if (n == laz::kVariableChunkSize)
    n = laz_test::get<std::uint32_t>(f.bytes, static_cast<std::size_t>(p - f.bytes.data()) + f.record_length);
  return static_cast<std::size_t>(std::min<std::uint64_t>(n, f.point_count - done));
}

bool
benchmarkFile(const std::string& path, int reps)
{
  laz_test::LasFile f;
  if (!laz_test::openLasFile(path, f)) {
    pcl::console::print_error("%s: not a LAS/LAZ file\n", path.c_str());
    return false;
  }
  const laz_test::WalkResult r = laz_test::walkLaz(f);
  if (!r.ok) {
    pcl::console::print_error("%s: %s\n", path.c_str(), r.error.c_str());
    return false;
  }
  std::string error;
  auto decoder = laz::makeChunkDecoder(r.vlr, error);
  auto encoder = laz::makeChunkEncoder(r.vlr, error);
  std::vector<std::uint8_t> records(r.records.size()), bytes;
  const auto decode = [&]() {
    const std::uint8_t* p = f.bytes.data() + f.offset_to_points + 8;
    for (std::uint64_t done = 0; done < f.point_count;) {
      const std::size_t n = chunkPoints(f, r.vlr, p, done);
      p += decoder->decode(p, f.bytes.data() + f.bytes.size(), n, records.data() + done * f.record_length,
                           error);
      done += n;
    }
  };
  const auto encode = [&]() {
    bytes.clear();
    for (std::uint64_t done = 0; done < f.point_count; done += r.vlr.chunk_size)
      encoder->encode(
          r.records.data() + done * f.record_length,
          static_cast<std::size_t>(std::min<std::uint64_t>(r.vlr.chunk_size, f.point_count - done)), bytes);
  };
  const auto dec = bestOf(reps, decode);
  const bool fixed = r.vlr.chunk_size != laz::kVariableChunkSize;
  const auto enc = fixed ? bestOf(reps, encode) : std::pair<double, double>{0, 0};
  const double n = double(f.point_count) / 1e6;
  std::printf("%-52s PF%d %8llu pts %6.2f B/pt ratio %5.2f  decode %5.2f (wall %5.2f)",
              path.substr(path.find_last_of('/') + 1).c_str(), f.point_format,
              static_cast<unsigned long long>(f.point_count),
              double(r.point_data_bytes) / double(f.point_count),
              double(r.records.size()) / double(r.point_data_bytes), n / dec.first, n / dec.second);
  if (fixed)
    std::printf("  encode %5.2f (wall %5.2f)", n / enc.first, n / enc.second);
  std::printf(" M points/s%s\n", records == r.records ? "" : "  DECODE MISMATCH");
  return records == r.records;
}

}  // namespace

int
main(int argc, char** argv)
{
  if (pcl::console::find_switch(argc, argv, "-h")) {
    std::printf("Usage: %s [FILE.laz ...] [-reps N]\n", argv[0]);
    return 0;
  }
  int reps = 5;
  pcl::console::parse_argument(argc, argv, "-reps", reps);
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-reps")
      ++i;
    else
      files.push_back(a);
  }
  if (files.empty()) {
    const std::string ign = std::string(PCL_LS3D_SHARED_DATA_DIR) + "/laz/ign/";
    files = {ign + "test_semis_2023_0292_6833_LA93_IGN69.laz", ign + "test_data_77050_627755_LA93_IGN69.laz",
             ign + "las_with_several_extra_byte_bloc.laz"};
  }
  if (reps < 1) {
    pcl::console::print_error("-reps must be at least 1\n");
    return 1;
  }
  std::printf("single thread, best of %d runs, M points/s of CPU time (and of wall time)\n", reps);
  bool ok = true;
  for (const std::string& path : files)
    ok = benchmarkFile(path, reps) && ok;
  return ok ? 0 : 1;
}
