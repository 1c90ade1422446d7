/// \file make_laz_seeds.cpp
/// \brief Writes small LAZ seeds for laz_decoder_fuzzer and copc_query_fuzzer:
///        `make_laz_seeds DIR [real.laz ...]`. Generated files: point formats 0-3 (LAS 1.2,
///        pointwise-chunked) and 6-8 (LAS 1.4, layered-chunked), with and without extra bytes,
///        1-300 points in chunks of 1, 7 and 50 points; real files named on the command line are
///        copied beside them (the small ones of shared/data/laz, COPC included).

#include <pcl_ls3d/io/las_io.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace {

pcl::PointCloud<pcl_ls3d::PointLiDAR>
randomCloud(std::size_t n, std::mt19937& rng)
{
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
  double t = 1000.0;
  for (std::size_t i = 0; i < n; ++i) {
    pcl_ls3d::PointLiDAR p;
    p.x = u(rng);
    p.y = u(rng);
    p.z = 0.1f * u(rng);
    p.intensity = static_cast<float>(rng() % 4096);
    p.number_of_returns = static_cast<std::uint8_t>(1 + rng() % 3);
    p.return_number = static_cast<std::uint8_t>(1 + rng() % p.number_of_returns);
    p.classification = static_cast<std::uint8_t>(rng() % 7);
    p.point_source_id = static_cast<std::uint16_t>(700 + rng() % 2);
    t += 1e-5 * (rng() % 100);
    p.gps_time = t;
    cloud.push_back(p);
  }
  return cloud;
}

/// A LAS file of `n` points in `format`, with `extra` bytes per record appended (set to a
/// pattern), compressed in chunks of `chunk` points.
bool
writeSeed(const std::string& path, int format, std::size_t n, std::size_t extra, std::uint32_t chunk,
          std::mt19937& rng)
{
  pcl_ls3d::io::SaveOptions so;
  so.las_point_format = static_cast<std::uint8_t>(format);
  so.las_minor_version = format >= 6 ? 4 : 2;
  std::vector<std::uint8_t> las, laz;
  std::string error;
  if (!pcl_ls3d::io::writeLas(randomCloud(n, rng), Eigen::Vector3d(500000, 5000000, 0), las, error, so))
    return std::fprintf(stderr, "%s: %s\n", path.c_str(), error.c_str()), false;
  if (extra > 0) {  // widen every record by `extra` bytes
    std::uint32_t offset;
    std::uint16_t length;
    std::memcpy(&offset, las.data() + 96, 4);
    std::memcpy(&length, las.data() + 105, 2);
    std::vector<std::uint8_t> wide(las.begin(), las.begin() + offset);
    for (std::size_t i = 0; i < n; ++i) {
      const auto r = las.begin() + offset + static_cast<std::ptrdiff_t>(i * length);
      wide.insert(wide.end(), r, r + length);
      for (std::size_t e = 0; e < extra; ++e)
        wide.push_back(static_cast<std::uint8_t>(i * 7 + e));
    }
    const std::uint16_t wider = static_cast<std::uint16_t>(length + extra);
    std::memcpy(wide.data() + 105, &wider, 2);
    las.swap(wide);
  }
  if (!pcl_ls3d::io::compressLas(las.data(), las.size(), laz, error, chunk))
    return std::fprintf(stderr, "%s: %s\n", path.c_str(), error.c_str()), false;
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(laz.data()), static_cast<std::streamsize>(laz.size()));
  return true;
}

}  // namespace

int
main(int argc, char** argv)
{
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s DIR [real.laz ...]\n", argv[0]);
    return 1;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  std::mt19937 rng(42);
  int written = 0;
  for (int format : {0, 1, 2, 3, 6, 7, 8})
    for (std::size_t extra : {0, 5})
      for (const auto& [n, chunk] : {std::pair<std::size_t, std::uint32_t>{1, 1}, {20, 7}, {300, 50}}) {
        const std::string name = "gen_pf" + std::to_string(format) + "_eb" + std::to_string(extra) + "_n" +
                                 std::to_string(n) + ".laz";
        written += writeSeed((dir / name).string(), format, n, extra, chunk, rng);
      }
  for (int i = 2; i < argc; ++i) {
    std::error_code ec;
    std::filesystem::copy_file(argv[i], dir / std::filesystem::path(argv[i]).filename(),
                               std::filesystem::copy_options::overwrite_existing, ec);
    written += !ec;
  }
  std::printf("%d seeds in %s\n", written, dir.c_str());
  return 0;
}
