#pragma once
/// \file hostile_files.h
/// \brief Crafted files whose headers claim far more than they hold (issue 12), shared by the
///        error-message tests and the memory-bound tests: a 10-point PCD that says a billion
///        points (ASCII, binary, binary_compressed), PLY files with a negative or a 2^32 - 1
///        vertex count, and the error each must give.

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace pcl_ls3d_test {

struct CraftedFile
{
  std::string name;    ///< file name; the extension picks the reader
  std::string bytes;   ///< file content
  std::string expect;  ///< a part of the one-line error
};

/// A PCD header for x y z float with the given counts and DATA kind.
inline std::string
pcdHeader(const std::string& width, const std::string& points, const std::string& data)
{
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
         "TYPE F F F\nCOUNT 1 1 1\nWIDTH " +
         width + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + points + "\nDATA " + data + "\n";
}

inline std::string
uint32Bytes(std::uint32_t v)
{
  std::string s(4, '\0');
  std::memcpy(&s[0], &v, 4);
  return s;
}

/// `n` little-endian float triplets (i, 2i, 3i).
inline std::string
floatTriplets(int n)
{
  std::string s;
  for (int i = 0; i < n; ++i)
    for (int k = 1; k <= 3; ++k) {
      const float f = static_cast<float>(k * i);
      s.append(reinterpret_cast<const char*>(&f), 4);
    }
  return s;
}

inline std::string
plyHeader(const std::string& format, const std::string& count)
{
  return "ply\nformat " + format + " 1.0\ncomment crafted\nelement vertex " + count +
         "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
}

inline std::vector<CraftedFile>
hostileFiles()
{
  const std::string billion = "1000000000";
  std::string ascii_points;
  for (int i = 0; i < 10; ++i)
    ascii_points += std::to_string(i) + " " + std::to_string(2 * i) + " 1.5\n";
  // 10 points of LZF literal runs (control byte 11 = 12 literal bytes follow).
  std::string lzf;
  for (const char c : floatTriplets(10)) {
    if (lzf.size() % 13 == 0)
      lzf.push_back(11);
    lzf.push_back(c);
  }
  return {
      {"billion_ascii.pcd", pcdHeader(billion, billion, "ascii") + ascii_points,
       "header says 1000000000 points"},
      {"billion_binary.pcd", pcdHeader(billion, billion, "binary") + floatTriplets(10),
       "header says 1000000000 points"},
      {"billion_compressed.pcd",
       pcdHeader(billion, billion, "binary_compressed") + uint32Bytes(std::uint32_t(lzf.size())) +
           uint32Bytes(120) + lzf,
       "header says 1000000000 points"},
      {"hundred_million_compressed.pcd",
       pcdHeader("100000000", "100000000", "binary_compressed") + uint32Bytes(std::uint32_t(lzf.size())) +
           uint32Bytes(1200000000u) + lzf,
       "LZF bytes expand at most 100 times"},
      {"negative_width.pcd", pcdHeader("-5", "10", "ascii") + ascii_points, "WIDTH '-5'"},
      {"width_points_mismatch.pcd", pcdHeader("11", "10", "ascii") + ascii_points, "is not POINTS 10"},
      {"negative_vertex.ply", plyHeader("ascii", "-5") + "1 2 3\n", "count '-5' is not an integer in 0.."},
      {"huge_vertex_ascii.ply", plyHeader("ascii", "4294967295") + "1 2 3\n4 5 6\n",
       "header says 4294967295 vertex items"},
      {"huge_vertex_binary.ply", plyHeader("binary_little_endian", "4294967295") + floatTriplets(2),
       "header says 4294967295 vertex items"},
      {"huge_vertex_big_endian.ply",
       plyHeader("binary_big_endian", "18446744073709551615") + floatTriplets(2), "is not an integer in 0.."},
  };
}

}  // namespace pcl_ls3d_test
