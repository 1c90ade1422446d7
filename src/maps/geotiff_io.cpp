#include <pcl_ls3d/maps/geotiff_io.h>

#include "gdal_session.h"

#include <cpl_string.h>

#include <cmath>
#include <limits>
#include <sys/stat.h>

namespace pcl_ls3d {
namespace maps {

namespace {

bool
fileExists(const std::string& path)
{
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

}  // namespace

bool
writeGeoTiff(const std::string& path, const Raster& raster, const std::string& crs_wkt, std::string& error,
             bool overwrite)
{
  if (!raster.grid.valid() || raster.values.size() != raster.grid.size()) {
    error = "cannot write an empty or inconsistent raster to " + path;
    return false;
  }
  if (!overwrite && fileExists(path)) {
    error = path + " exists (not overwritten)";
    return false;
  }
  detail::QuietGdal quiet;
  GDALDriverH driver = GDALGetDriverByName("GTiff");
  if (!driver) {
    error = "GDAL has no GTiff driver";
    return false;
  }
  char** options = nullptr;
  options = CSLSetNameValue(options, "COMPRESS", "DEFLATE");
  options = CSLSetNameValue(options, "PREDICTOR", "3");  // floating-point predictor
  if (raster.grid.cols > 512 || raster.grid.rows > 512)
    options = CSLSetNameValue(options, "TILED", "YES");
  GDALDatasetH ds =
      GDALCreate(driver, path.c_str(), raster.grid.cols, raster.grid.rows, 1, GDT_Float32, options);
  CSLDestroy(options);
  if (!ds) {
    error = "cannot create " + path + ": " + detail::QuietGdal::lastError();
    return false;
  }
  std::array<double, 6> gt = raster.grid.geoTransform();
  bool ok = GDALSetGeoTransform(ds, gt.data()) == CE_None;
  if (ok && !crs_wkt.empty())
    ok = GDALSetProjection(ds, crs_wkt.c_str()) == CE_None;
  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  ok = ok && GDALSetRasterNoDataValue(band, std::numeric_limits<double>::quiet_NaN()) == CE_None;
  ok = ok && GDALRasterIO(band, GF_Write, 0, 0, raster.grid.cols, raster.grid.rows,
                          const_cast<float*>(raster.values.data()), raster.grid.cols, raster.grid.rows,
                          GDT_Float32, 0, 0) == CE_None;
  if (!ok)
    error = "cannot write " + path + ": " + detail::QuietGdal::lastError();
  GDALClose(ds);  // flushes
  return ok;
}

bool
readGeoTiff(const std::string& path, Raster& raster, std::string& crs_wkt, std::string& error)
{
  detail::QuietGdal quiet;
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  if (!ds) {
    error = "cannot open " + path + ": " + detail::QuietGdal::lastError();
    return false;
  }
  std::array<double, 6> gt{};
  const bool georef = GDALGetGeoTransform(ds, gt.data()) == CE_None;
  if (!georef || gt[2] != 0.0 || gt[4] != 0.0 || !(gt[1] > 0.0) || std::abs(gt[1] + gt[5]) > 1e-9 * gt[1]) {
    GDALClose(ds);
    error = path + " is not a north-up raster with square cells";
    return false;
  }
  GridGeometry g;
  g.min_x = gt[0];
  g.max_y = gt[3];
  g.cell = gt[1];
  g.cols = GDALGetRasterXSize(ds);
  g.rows = GDALGetRasterYSize(ds);
  raster = Raster(g);
  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  bool ok = band && GDALRasterIO(band, GF_Read, 0, 0, g.cols, g.rows, raster.values.data(), g.cols, g.rows,
                                 GDT_Float32, 0, 0) == CE_None;
  if (ok) {
    int has_nodata = 0;
    const double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
    if (has_nodata && !std::isnan(nodata))
      for (float& v : raster.values)
        if (v == static_cast<float>(nodata))
          v = std::numeric_limits<float>::quiet_NaN();
    const char* ref = GDALGetProjectionRef(ds);
    crs_wkt = ref ? ref : "";
  } else
    error = "cannot read " + path + ": " + detail::QuietGdal::lastError();
  GDALClose(ds);
  return ok;
}

}  // namespace maps
}  // namespace pcl_ls3d
