/// \file test_reader_agreement.cpp
/// \brief pcl_ls3d's own PCD and PLY readers against PCL's (an independent implementation): files
///        written by PCL's writers in every encoding and with every field type, and every PCD in
///        the shared data (skipped when it is absent), give the same points and attributes.

#include <pcl_ls3d/io/cloud_io.h>

#include "io/io_test_utils.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

using namespace pcl_ls3d;
using pcl_ls3d_test::TempDir;
namespace fs = std::filesystem;

namespace {

/// Field `name` of point `i` of a PCLPointCloud2, as double (NaN when there is no such field).
double
valueOf(const pcl::PCLPointCloud2& c, std::size_t i, const std::string& name)
{
  const int k = pcl::getFieldIndex(c, name);
  if (k < 0)
    return std::nan("");
  const pcl::PCLPointField& f = c.fields[static_cast<std::size_t>(k)];
  const std::uint8_t* p = c.data.data() + i * c.point_step + f.offset;
  auto get = [p](auto v) {
    std::memcpy(&v, p, sizeof(v));
    return static_cast<double>(v);
  };
  switch (f.datatype) {
  case pcl::PCLPointField::INT8:
    return get(std::int8_t());
  case pcl::PCLPointField::UINT8:
    return get(std::uint8_t());
  case pcl::PCLPointField::INT16:
    return get(std::int16_t());
  case pcl::PCLPointField::UINT16:
    return get(std::uint16_t());
  case pcl::PCLPointField::INT32:
    return get(std::int32_t());
  case pcl::PCLPointField::UINT32:
    return get(std::uint32_t());
  case pcl::PCLPointField::FLOAT32:
    return get(float());
  default:
    return get(double());
  }
}

/// Loads `path` with loadCloud and with PCL's reader and compares every finite point.
void
expectAgreement(const std::string& path, bool ply)
{
  SCOPED_TRACE(path);
  pcl::PCLPointCloud2 ref;
  ASSERT_EQ(ply ? pcl::io::loadPLYFile(path, ref) : pcl::io::loadPCDFile(path, ref), 0);
  pcl::PointCloud<PointLiDAR> cloud;
  io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(io::loadCloud(path, cloud, info, error)) << error;
  const std::size_t n = static_cast<std::size_t>(ref.width) * ref.height;
  EXPECT_EQ(info.points_in_file, n);
  const bool has_label = pcl::getFieldIndex(ref, "label") >= 0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d x(valueOf(ref, i, "x"), valueOf(ref, i, "y"), valueOf(ref, i, "z"));
    if (!x.allFinite())
      continue;
    ASSERT_LT(j, cloud.size());
    const Eigen::Vector3d got = cloud[j].getVector3fMap().cast<double>() + info.origin;
    EXPECT_LT((got - x).cwiseAbs().maxCoeff(),
              1e-6 * (1.0 + x.cwiseAbs().maxCoeff()) + (info.origin.isZero() ? 0.0 : 1e-3));
    const double intensity = valueOf(ref, i, "intensity");
    if (std::isfinite(intensity)) {
      EXPECT_FLOAT_EQ(cloud[j].intensity, static_cast<float>(intensity));
    }
    if (has_label) {
      EXPECT_EQ(cloud[j].classification, std::min(255.0, valueOf(ref, i, "label")));
    }
    ++j;
  }
  EXPECT_EQ(j, cloud.size());
  EXPECT_EQ(info.points_dropped_nonfinite, n - j);
}

/// 500 points: x double, y z float, intensity uint16, label uint32, a 3-float normal, an int8, one
/// NaN point; written by PCL.
pcl::PCLPointCloud2
mixedCloud()
{
  pcl::PCLPointCloud2 c;
  const std::pair<const char*, std::uint8_t> fields[] = {
      {"x", pcl::PCLPointField::FLOAT64},    {"y", pcl::PCLPointField::FLOAT32},
      {"z", pcl::PCLPointField::FLOAT32},    {"intensity", pcl::PCLPointField::UINT16},
      {"label", pcl::PCLPointField::UINT32}, {"normal", pcl::PCLPointField::FLOAT32},
      {"flag", pcl::PCLPointField::INT8}};
  for (const auto& [name, type] : fields) {
    pcl::PCLPointField f;
    f.name = name;
    f.datatype = type;
    f.count = std::string(name) == "normal" ? 3 : 1;
    f.offset = c.point_step;
    c.point_step += static_cast<std::uint32_t>(pcl::getFieldSize(type) * f.count);
    c.fields.push_back(f);
  }
  c.width = 500;
  c.height = 1;
  c.row_step = c.point_step * c.width;
  c.data.resize(c.row_step);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-900.0, 900.0);
  for (std::size_t i = 0; i < c.width; ++i) {
    std::uint8_t* p = c.data.data() + i * c.point_step;
    const double x = i == 7 ? std::nan("") : u(rng);
    const float y = static_cast<float>(u(rng)), z = static_cast<float>(u(rng));
    const std::uint16_t intensity = static_cast<std::uint16_t>(rng());
    const std::uint32_t label = static_cast<std::uint32_t>(rng() % 300);
    std::memcpy(p, &x, 8);
    std::memcpy(p + 8, &y, 4);
    std::memcpy(p + 12, &z, 4);
    std::memcpy(p + 16, &intensity, 2);
    std::memcpy(p + 18, &label, 4);
    p[34] = static_cast<std::uint8_t>(rng());
  }
  return c;
}

}  // namespace

// PCL's PCDWriter in ASCII, binary and binary_compressed; PCL's PLYWriter in ASCII and binary.
TEST(ReaderAgreement, FilesWrittenByPclReadTheSameAsWithPcl)
{
  TempDir dir("ls3d_agree");
  const pcl::PCLPointCloud2 c = mixedCloud();
  pcl::PCDWriter pcd;
  ASSERT_EQ(pcd.writeASCII(dir.file("a.pcd"), c, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity(), 17),
            0);
  ASSERT_EQ(pcd.writeBinary(dir.file("b.pcd"), c), 0);
  ASSERT_EQ(pcd.writeBinaryCompressed(dir.file("c.pcd"), c), 0);
  pcl::PLYWriter ply;
  ASSERT_EQ(ply.writeASCII(dir.file("a.ply"), c), 0);
  ASSERT_EQ(ply.writeBinary(dir.file("b.ply"), c), 0);
  for (const char* name : {"a.pcd", "b.pcd", "c.pcd"})
    expectAgreement(dir.file(name), false);
  for (const char* name : {"a.ply", "b.ply"})
    expectAgreement(dir.file(name), true);
}

// Every PCD of the shared data (Kinect frames in binary_compressed with NaN, binary keypoints,
// ASCII bunnies and DTMs) reads the same as with PCL.
TEST(ReaderAgreement, SharedDataPcdFilesReadTheSameAsWithPcl)
{
  const fs::path root(PCL_LS3D_SHARED_DATA_DIR);
  if (!fs::is_directory(root))
    GTEST_SKIP() << "shared data folder " << root << " is absent; real-data test skipped";
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    if (entry.path().extension() == ".pcd") {
      expectAgreement(entry.path().string(), false);
      ++files;
    }
  EXPECT_GT(files, 0u);
}
