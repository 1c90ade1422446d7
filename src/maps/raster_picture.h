#pragma once
// Private: a raster as the pixels of a map and the outline of marked cells, in map pixels.
#include <pcl_ls3d/maps/colour_map.h>
#include <pcl_ls3d/maps/image.h>
#include <pcl_ls3d/maps/raster.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_ls3d {
namespace maps {
namespace detail {

/// The raster in colour at the map's size: each cell a block of \a scale × \a scale pixels when
/// \a scale ≥ 1 (a whole number), else each pixel the mean of the finite cells under it.
/// Enlarged here rather than by the drawing: SVG viewers smooth an enlarged image.
Image
cellPixels(const Raster& raster, double scale, const ColourMap& colours, Rgb no_data);

/// \a marked at a map's pixels for \a scale < 1: 1 where a marked cell lies under a pixel.
Raster
markedPixels(const Raster& marked, double scale);

/// The border between cells of \a marked holding values > 0.5 and the other cells (or the
/// grid's edge), as horizontal and vertical lines in pixels of a map whose top left corner is
/// (x0, y0) and whose cells are \a scale pixels wide, each moved \a inset into the marked cells
/// (half the line width: the line then lies on the marked cells' border pixels, and flat ends
/// meet at the corners); runs along one row or column are joined. At \a scale < 1 the border
/// of the pixels under which a marked cell lies.
std::vector<Eigen::Vector4d>
outlineSegments(const Raster& marked, double scale, double x0, double y0, double inset);

}  // namespace detail
}  // namespace maps
}  // namespace pcl_ls3d
