#pragma once
/// \file deformation_map.h
/// \brief The map of a deformation analysis (issue 9): the residual of every epoch point on a
///        grid, drawn with a diverging colour bar (blue: the epoch lies below / inside the
///        reference, red: above / outside) and the cells of the significant regions outlined;
///        written as a PNG, PDF or SVG and as a float32 GeoTIFF carrying the input's CRS (maps
///        library).
///
/// Cells are 1.5 point spacings by default (on a grid every cell holds a point) on the plane the
/// regions were counted on (xy for terrain); a cell holds the mean residual of its points.
/// Irregular airborne sampling leaves many such cells empty: give a larger `cell` there (the
/// regions' adjacency, 2.5 spacings, holds about six points per cell). The colour range
/// is symmetric, ±(the 98th percentile of |r|, at least 2 k σ̂) rounded up to a nice number, so
/// the significance threshold k σ̂ lies inside the bar.

#include <pcl_ls3d/deformation/deformation_analysis.h>
#include <pcl_ls3d/maps/drawing.h>
#include <pcl_ls3d/maps/map_format.h>
#include <pcl_ls3d/maps/map_rendering.h>
#include <pcl_ls3d/maps/raster.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace deformation {

/// \brief Text and georeference of a deformation map.
struct DeformationMapSettings
{
  std::string title = "Deformation";
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< added to the points (file coordinates)
  std::string crs_wkt;  ///< CRS of the inputs (empty: none; the GeoTIFF then has no CRS)
  double k = 3.0;       ///< significance factor used (the colour range covers 2 k σ̂)
  bool lod95 = false;   ///< significance by the 95 % level of detection instead of k σ
  double cell = 0.0;    ///< cell edge; 0: 1.5 × the regions' point spacing
  /// Said under the title when the heights were converted to the plan unit before matching
  /// (HeightUnits), e.g. "heights converted to m (x 0.3048006) before matching"; empty:
  /// heights as the files store them.
  std::string heights_note;
};

/// \brief The rasters and the drawn map.
struct DeformationMap
{
  maps::Raster residual;   ///< mean residual per cell, NaN where no point has one
  maps::Raster in_region;  ///< 1 where a point of a significant region falls, 0 elsewhere
  maps::Drawing drawing;   ///< the map (empty when nothing could be drawn)
  maps::MapStyle style;    ///< its text: title, subtitle, colour-bar unit, footer
  double limit = 0.0;      ///< the colour range is [−limit, +limit]
  std::string why_empty;   ///< why the drawing is empty, when not for want of residuals (too many cells)
};

/// Builds the rasters and draws the map of `result` over `epoch` (the points analysed, epoch
/// order, local coordinates). An empty drawing when no point has a residual.
DeformationMap
makeDeformationMap(const std::vector<Eigen::Vector3d>& epoch, const DeformationResult& result,
                   const DeformationMapSettings& settings);

/// Writes PREFIX.png, .pdf or .svg (the map, in `format`) and PREFIX.tif (the residual raster,
/// NaN no data, with `crs_wkt` when not empty); refuses existing files unless `overwrite`. False
/// with a reason.
bool
writeDeformationMap(const std::string& prefix, const DeformationMap& map, const std::string& crs_wkt,
                    bool overwrite, std::string& error, maps::MapFormat format = maps::MapFormat::PNG);

}  // namespace deformation
}  // namespace pcl_ls3d
