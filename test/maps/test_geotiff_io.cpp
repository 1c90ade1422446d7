// GeoTIFF and CRS (maps/geotiff_io.h, coordinate_reference.h): values, no-data, geotransform and
// CRS survive a write/read through GDAL; LAS GeoTIFF keys and WKT VLRs give the CRS GDAL reads
// from them (synthetic keys, and the real IGN files when ../shared/data is present).
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/maps/geotiff_io.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

using namespace pcl_ls3d;
using namespace pcl_ls3d::maps;

namespace {

std::string
tempPath(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("pcl_ls3d_geotiff_" + name)).string();
}

io::LasVlr
geoKeyVlr(const std::vector<std::uint16_t>& keys)
{
  io::LasVlr v;
  v.user_id = "LASF_Projection";
  v.record_id = 34735;
  v.data.resize(keys.size() * 2);
  std::memcpy(v.data.data(), keys.data(), v.data.size());
  return v;
}

}  // namespace

TEST(GeoTiff, WriteReadKeepsValuesNoDataGeometryAndCrs)
{
  Raster r(GridGeometry::covering({770500.0, 6277550.0}, {770549.0, 6277579.0}, 0.5));
  for (std::size_t k = 0; k < r.values.size(); ++k)
    r.values[k] = static_cast<float>(0.001 * static_cast<double>(k % 97) - 0.05);
  r.values[7] = NAN;
  const std::string wkt = crsFromUserInput("EPSG:2154");
  ASSERT_FALSE(wkt.empty());
  const std::string path = tempPath("a.tif");
  std::remove(path.c_str());
  std::string error;
  ASSERT_TRUE(writeGeoTiff(path, r, wkt, error)) << error;
  EXPECT_FALSE(writeGeoTiff(path, r, wkt, error));  // never replaced silently
  EXPECT_NE(error.find("exists"), std::string::npos);
  Raster back;
  std::string back_wkt;
  ASSERT_TRUE(readGeoTiff(path, back, back_wkt, error)) << error;
  EXPECT_EQ(back.grid.cols, r.grid.cols);
  EXPECT_EQ(back.grid.rows, r.grid.rows);
  EXPECT_DOUBLE_EQ(back.grid.min_x, r.grid.min_x);
  EXPECT_DOUBLE_EQ(back.grid.max_y, r.grid.max_y);
  EXPECT_DOUBLE_EQ(back.grid.cell, 0.5);
  ASSERT_EQ(back.values.size(), r.values.size());
  EXPECT_TRUE(std::isnan(back.values[7]));
  for (std::size_t k = 0; k < r.values.size(); ++k) {
    if (k != 7) {
      ASSERT_EQ(back.values[k], r.values[k]) << k;
    }
  }
  EXPECT_TRUE(sameCrs(back_wkt, wkt));
  EXPECT_NE(crsName(back_wkt).find("Lambert-93"), std::string::npos);
  EXPECT_DOUBLE_EQ(crsLinearUnit(back_wkt), 1.0);
  std::remove(path.c_str());
}

TEST(GeoTiff, RasterWithoutCrsAndBadPaths)
{
  Raster r(GridGeometry::covering({0, 0}, {9, 9}, 1.0));
  std::fill(r.values.begin(), r.values.end(), 1.0f);
  const std::string path = tempPath("nocrs.tif");
  std::remove(path.c_str());
  std::string error, wkt;
  ASSERT_TRUE(writeGeoTiff(path, r, "", error)) << error;
  Raster back;
  ASSERT_TRUE(readGeoTiff(path, back, wkt, error)) << error;
  EXPECT_TRUE(wkt.empty());
  std::remove(path.c_str());
  EXPECT_FALSE(writeGeoTiff("/nonexistent_dir/x.tif", r, "", error));
  EXPECT_FALSE(readGeoTiff(tempPath("missing.tif"), back, wkt, error));
  EXPECT_FALSE(writeGeoTiff(path, Raster(), "", error));
}

TEST(CoordinateReference, GeoTiffKeysOfALasFile)
{
  // Lambert-93 (ProjectedCSTypeGeoKey 3072 = 2154), metres, and NGF-IGN69 heights (4096 = 5720).
  const std::vector<std::uint16_t> keys = {1,    1, 0, 5,    1024, 0, 1, 1,    1025, 0, 1, 1,
                                           3072, 0, 1, 2154, 3076, 0, 1, 9001, 4096, 0, 1, 5720};
  const std::string wkt = crsFromLasVlrs({geoKeyVlr(keys)});
  ASSERT_FALSE(wkt.empty());
  EXPECT_TRUE(sameCrs(wkt, crsFromUserInput("EPSG:2154+5720"))) << wkt;
  // Horizontal keys only.
  const std::vector<std::uint16_t> horizontal = {1, 1, 0, 2, 1024, 0, 1, 1, 3072, 0, 1, 32642};
  EXPECT_TRUE(sameCrs(crsFromLasVlrs({geoKeyVlr(horizontal)}), crsFromUserInput("EPSG:32642")));
  // Nothing: empty. An unknown user CRS: empty, with a reason.
  EXPECT_TRUE(crsFromLasVlrs({}).empty());
  std::string why;
  EXPECT_TRUE(crsFromUserInput("EPSG:99999999", &why).empty());
  EXPECT_FALSE(why.empty());
}

TEST(CoordinateReference, OgcWktVlr)
{
  io::LasVlr v;
  v.user_id = "LASF_Projection";
  v.record_id = 2112;
  const std::string wkt = crsFromUserInput("EPSG:2975");
  v.data.assign(wkt.begin(), wkt.end());
  v.data.push_back(0);
  EXPECT_TRUE(sameCrs(crsFromLasVlrs({v}), wkt));
}

// The real files: LAS 1.2 with GeoTIFF keys (ctview) and LAS 1.4 with a WKT VLR (IGN tiles).
TEST(CoordinateReference, RealIgnFilesDeclareLambert93)
{
  const std::string dir = PCL_LS3D_SHARED_DATA_DIR;
  const std::string files[] = {dir + "/segmentation/ctview__test_data_77055_627760_LA93_IGN69.las",
                               dir + "/registration/ign_lidarhd/test_data_77055_627760_LA93_IGN69.las"};
  if (!std::filesystem::exists(files[0]) || !std::filesystem::exists(files[1]))
    GTEST_SKIP() << "shared data not found in " << dir;
  for (const std::string& f : files) {
    pcl::PointCloud<PointLiDAR> cloud;
    io::CloudInfo info;
    std::string error;
    ASSERT_TRUE(io::loadCloud(f, cloud, info, error)) << error;
    std::string why;
    const std::string wkt = crsFromLasVlrs(info.las.vlrs, &why);
    ASSERT_FALSE(wkt.empty()) << f << ": " << why;
    EXPECT_NE(crsName(wkt).find("Lambert-93"), std::string::npos) << crsName(wkt);
    EXPECT_DOUBLE_EQ(crsLinearUnit(wkt), 1.0);
  }
}

// Heights take the vertical CRS's unit where there is one (PDAL's autzen-bmx: metres in plan,
// US survey feet in height), else the plan's (Autzen's trimmed strip: feet throughout).
TEST(CoordinateReference, VerticalUnit)
{
  EXPECT_DOUBLE_EQ(crsVerticalUnit(crsFromUserInput("EPSG:2154")), 1.0);
  EXPECT_NEAR(crsVerticalUnit(crsFromUserInput("EPSG:2994")), 0.3048, 1e-12);
  const std::string compound = crsFromUserInput("EPSG:26910+6360");  // UTM 10N + NAVD88 (ftUS)
  ASSERT_FALSE(compound.empty());
  EXPECT_DOUBLE_EQ(crsLinearUnit(compound), 1.0);
  EXPECT_NEAR(crsVerticalUnit(compound), 1200.0 / 3937.0, 1e-9);
  EXPECT_EQ(crsVerticalUnit(crsFromUserInput("EPSG:4326")), 0.0);  // geographic: unknown
  EXPECT_EQ(crsVerticalUnit(""), 0.0);
  // Angles and earth-centred coordinates are no plan and height (pcl_ls3d_segment refuses them).
  EXPECT_TRUE(crsIsGeographic(crsFromUserInput("EPSG:4326+5773")));  // WGS 84 + EGM96 height
  EXPECT_FALSE(crsIsGeographic(compound));
  EXPECT_TRUE(crsIsGeocentric(crsFromUserInput("EPSG:4978")));
  EXPECT_FALSE(crsIsGeocentric(crsFromUserInput("EPSG:2154")));
}
