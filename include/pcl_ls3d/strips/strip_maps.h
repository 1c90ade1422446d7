#pragma once
/// \file strip_maps.h
/// \brief The maps a client looks at: per overlap the signed normal discrepancy before and
///        after adjustment as a GeoTIFF (in the input's CRS) and a map (PNG, PDF or SVG) with
///        lasoverlap-style tolerance classes (±0.10 / ±0.20 m by default), a mosaic of all
///        overlaps before and after, and histograms of the discrepancies before and after.

#include <pcl_ls3d/maps/map_format.h>
#include <pcl_ls3d/strips/strip_adjustment_report.h>
#include <pcl_ls3d/strips/strip_block_adjustment.h>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace strips {

/// \brief What to draw and how.
struct StripMapSettings
{
  double inner = 0.10;  ///< tolerance class limits in metres (converted to the data's unit)
  double outer = 0.20;
  double cell = 0.0;     ///< raster cell in data units; 0 = 2 × the overlap's observation spacing
  std::string crs_wkt;   ///< written into the GeoTIFFs; its unit labels the maps
  bool geotiff = true;   ///< the discrepancy rasters as GeoTIFF
  bool pictures = true;  ///< the maps and histograms, drawn in `format`
  maps::MapFormat format = maps::MapFormat::PNG;
};

/// Writes the maps into `dir` (which must exist); the names written are appended to `written`.
/// Refuses to replace existing files. False with a one-line reason.
bool
writeStripMaps(const StripAdjustmentReport& report, const StripPlan& plan,
               const std::vector<OverlapSamples>& samples, const std::string& dir,
               const StripMapSettings& settings, std::vector<std::string>& written, std::string& error);

}  // namespace strips
}  // namespace pcl_ls3d
