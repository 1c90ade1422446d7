/// \file pcd_writer.cpp
/// \brief Binary PCD with header comment lines: the recorded origin, the CRS (pcd_io.h).

#include <pcl_ls3d/io/pcd_io.h>

#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <utility>

namespace pcl_ls3d {
namespace io {
namespace {

/// The fields back to back in offset order: a PCD stores exactly what its header lists, and
/// PCDWriter's header for a PCLPointCloud2 lists no padding (a registered point type has some).
pcl::PCLPointCloud2
packedFields(const pcl::PCLPointCloud2& in)
{
  std::vector<pcl::PCLPointField> fields = in.fields;
  std::sort(fields.begin(), fields.end(), [](const auto& a, const auto& b) { return a.offset < b.offset; });
  pcl::PCLPointCloud2 out;
  out.width = in.width;
  out.height = in.height;
  out.is_dense = in.is_dense;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> copies;  // (offset in `in`, bytes)
  std::uint32_t offset = 0;
  for (pcl::PCLPointField f : fields) {
    const auto bytes = static_cast<std::uint32_t>(pcl::getFieldSize(f.datatype)) * f.count;
    copies.emplace_back(f.offset, bytes);
    f.offset = offset;
    offset += bytes;
    out.fields.push_back(f);
  }
  out.point_step = offset;
  out.row_step = offset * out.width;
  const std::size_t points = static_cast<std::size_t>(in.width) * in.height;
  out.data.resize(points * offset);
  for (std::size_t i = 0; i < points; ++i) {
    const std::uint8_t* from = in.data.data() + i * in.point_step;
    std::uint8_t* to = out.data.data() + i * offset;
    for (const auto& [at, bytes] : copies) {
      std::memcpy(to, from + at, bytes);
      to += bytes;
    }
  }
  return out;
}

}  // namespace

bool
savePcdBinaryWithOrigin(const std::string& path, const pcl::PCLPointCloud2& cloud,
                        const Eigen::Vector3d& origin, const std::string& comments, std::string& error)
{
  return savePcdBinaryWithComments(path, cloud, pcdOriginLine(origin) + "\n" + comments, error);
}

bool
savePcdBinaryWithComments(const std::string& path, const pcl::PCLPointCloud2& cloud,
                          const std::string& comments, std::string& error)
{
  if (cloud.data.size() < static_cast<std::size_t>(cloud.width) * cloud.height * cloud.point_step) {
    error = "cannot write '" + path + "': the cloud holds fewer bytes than its points need";
    return false;
  }
  const pcl::PCLPointCloud2 packed = packedFields(cloud);
  // PCDWriter cannot add comment lines: its own header, ours after its first line.
  std::string header =
      pcl::PCDWriter().generateHeaderBinary(packed, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity());
  const std::size_t first = header.find('\n');
  header.insert(first == std::string::npos ? 0 : first + 1, comments);
  header += "DATA binary\n";  // generateHeaderBinary() stops before it, as writeBinary() adds it
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << header;
  f.write(reinterpret_cast<const char*>(packed.data.data()),
          static_cast<std::streamsize>(packed.data.size()));
  f.close();
  if (!f) {
    error = "cannot write '" + path + "'";
    return false;
  }
  return true;
}

}  // namespace io
}  // namespace pcl_ls3d
