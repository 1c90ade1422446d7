#pragma once
/// \file geotiff_io.h
/// \brief Rasters as single-band float32 GeoTIFF through GDAL (Debian libgdal), north up, NaN
///        as the no-data value, with the CRS written when one is given.

#include <pcl_ls3d/maps/raster.h>

#include <string>

namespace pcl_ls3d {
namespace maps {

/// Writes `raster` (deflate-compressed, tiled when large) with the CRS in `crs_wkt` (empty: no
/// CRS); refuses to replace an existing file unless `overwrite`. False with a one-line reason.
bool
writeGeoTiff(const std::string& path, const Raster& raster, const std::string& crs_wkt, std::string& error,
             bool overwrite = false);

/// Reads band 1 of a north-up raster GDAL can open (GeoTIFF or other) as float, the band's
/// no-data value mapped to NaN; `crs_wkt` receives its CRS (empty when none).
bool
readGeoTiff(const std::string& path, Raster& raster, std::string& crs_wkt, std::string& error);

}  // namespace maps
}  // namespace pcl_ls3d
