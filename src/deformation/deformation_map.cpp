#include <pcl_ls3d/deformation/deformation_map.h>

#include <pcl_ls3d/maps/colour_map.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/maps/geotiff_io.h>
#include <pcl_ls3d/maps/map_rendering.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

namespace pcl_ls3d {
namespace deformation {

namespace {

constexpr std::size_t kSubtitleWidth = 110;  // characters: about the width of the map and its bar

/// The two coordinates of a point on the plane the regions were counted on (x, y for z).
Eigen::Vector2d
planar(const Eigen::Vector3d& p, int normal_axis)
{
  return {p[(normal_axis + 1) % 3], p[(normal_axis + 2) % 3]};
}

/// The symmetric colour range: the 98th percentile of |r|, at least 2 k σ̂, rounded up to a
/// nice step.
double
colourLimit(std::vector<double> magnitudes, double k, double scale)
{
  const std::size_t q = magnitudes.size() * 98 / 100;
  std::nth_element(magnitudes.begin(), magnitudes.begin() + static_cast<std::ptrdiff_t>(q), magnitudes.end());
  double limit = std::max(magnitudes[q], 2.0 * k * scale);
  if (!(limit > 0.0))
    limit = 1.0;
  const double step = maps::niceStep(limit, 2);
  return std::ceil(limit / step) * step;
}

/// printf into a string of any length.
std::string
format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

std::string
format(const char* fmt, ...)
{
  va_list args, copy;
  va_start(args, fmt);
  va_copy(copy, args);
  const int n = std::vsnprintf(nullptr, 0, fmt, args);
  va_end(args);
  std::string out(static_cast<std::size_t>(std::max(n, 0)) + 1, '\0');
  std::vsnprintf(out.data(), out.size(), fmt, copy);
  va_end(copy);
  out.pop_back();
  return out;
}

/// `text` broken at spaces into lines of at most `width` characters (a longer word stays whole):
/// the estimator's name alone can exceed a map's width.
std::vector<std::string>
wrapped(const std::string& text, std::size_t width)
{
  std::vector<std::string> lines;
  std::string line, word;
  std::istringstream words(text);
  while (words >> word) {
    if (!line.empty() && line.size() + 1 + word.size() > width) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty())
    lines.push_back(line);
  return lines;
}

maps::MapStyle
mapStyle(const DeformationResult& r, const DeformationMapSettings& s, const maps::GridGeometry& grid,
         double limit)
{
  // Residuals and cells are in the unit of the coordinates: the CRS's, else the input's own.
  const std::string crs_unit = maps::crsLinearUnitName(s.crs_wkt);
  const std::string unit = crs_unit.empty() ? "input units" : crs_unit;
  maps::MapStyle style;
  style.title = s.title;
  const std::string test =
      s.lod95 ? "neighbourhood mean beyond its 95 % level of detection" : format("|r| > %g sigma", s.k);
  style.subtitle = wrapped(format("%s; robust scale %.3g %s, %zu of %zu points significant (%s)",
                                  r.matching.estimator.c_str(), r.matching.scale, unit.c_str(),
                                  r.field.significant_count, r.field.observed, test.c_str()),
                           kSubtitleWidth);
  style.subtitle.push_back(
      format("%.1f %% of the area in %zu deformed regions (outlined), %zu noise clusters",
             r.regions.percent_deformed, r.regions.regions.size(), r.regions.noise.size()));
  // Fewer parameters than asked: the client reading the map should know.
  for (const std::string& line : wrapped(r.model_note, kSubtitleWidth))
    style.subtitle.push_back(line);
  // Heights in another unit than x, y (a compound CRS): the residuals are in neither, unless
  // the heights were converted to the plan unit.
  if (!s.heights_note.empty())
    style.subtitle.push_back(s.heights_note);
  else if (maps::crsMixesUnits(s.crs_wkt))
    style.subtitle.push_back("WARNING: heights and plan coordinates in different units; the "
                             "residuals mix them");
  style.unit = unit;
  style.tick_format = limit >= 10 ? "%+.0f" : limit >= 1 ? "%+.1f" : "%+.2f";
  style.legend = {"epoch minus reference", "(mean per cell)", "outline: deformed region"};
  style.length_unit = crs_unit;  // no scale bar without a CRS (its unit unknown)
  const std::string crs = maps::crsName(s.crs_wkt);
  style.footer = format("cell %.3g %s, %d x %d cells, %s", grid.cell, unit.c_str(), grid.cols, grid.rows,
                        crs.empty() ? "no coordinate reference known" : crs.c_str());
  return style;
}

}  // namespace

DeformationMap
makeDeformationMap(const std::vector<Eigen::Vector3d>& epoch, const DeformationResult& r,
                   const DeformationMapSettings& s)
{
  DeformationMap out;
  const int axis = r.regions.plane_normal_axis;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  std::vector<double> magnitudes;
  for (std::size_t i = 0; i < epoch.size() && i < r.field.residual.size(); ++i)
    if (std::isfinite(r.field.residual[i]) && epoch[i].allFinite()) {
      const Eigen::Vector2d q = planar(epoch[i] + s.origin, axis);
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
      magnitudes.push_back(std::abs(r.field.residual[i]));
    }
  if (magnitudes.empty())
    return out;  // writeDeformationMap says "no residual to map"
  const double cell = s.cell > 0.0 ? s.cell : std::max(1.5 * r.regions.spacing, 1e-9);
  // Two rasters and their accumulators per cell: 40 M cells is ~1 GB, far beyond any picture.
  constexpr double kMaxCells = 4e7;
  const double cells = std::ceil((hi.x() - lo.x()) / cell + 1.0) * std::ceil((hi.y() - lo.y()) / cell + 1.0);
  if (!(cells <= kMaxCells)) {
    char buf[200];
    std::snprintf(buf, sizeof(buf), "a map cell of %.3g gives %.3g cells (at most %.3g): raise -map_cell",
                  cell, cells, kMaxCells);
    out.why_empty = buf;
    return out;
  }
  const maps::GridGeometry grid = maps::GridGeometry::covering(lo, hi, cell);
  maps::RasterAccumulator residual(grid, maps::RasterAccumulator::Mode::MEAN);
  maps::RasterAccumulator region(grid, maps::RasterAccumulator::Mode::MAX_ABS);
  for (std::size_t i = 0; i < epoch.size() && i < r.field.residual.size(); ++i)
    if (std::isfinite(r.field.residual[i]) && epoch[i].allFinite()) {
      const Eigen::Vector2d q = planar(epoch[i] + s.origin, axis);
      residual.add(q.x(), q.y(), r.field.residual[i]);
      region.add(q.x(), q.y(), i < r.regions.region.size() && r.regions.region[i] > 0 ? 1.0 : 0.0);
    }
  out.residual = residual.result();
  out.in_region = region.result();
  out.limit = colourLimit(std::move(magnitudes), s.k, r.matching.scale);
  const maps::ColourMap colours = maps::ColourMap::diverging(out.limit);
  out.style = mapStyle(r, s, grid, out.limit);
  out.drawing = maps::renderRasterMap(out.residual, colours, out.style, &out.in_region);
  return out;
}

bool
writeDeformationMap(const std::string& prefix, const DeformationMap& map, const std::string& crs_wkt,
                    bool overwrite, std::string& error, maps::MapFormat format)
{
  if (map.drawing.empty())
    return (error = map.why_empty.empty() ? "no residual to map" : map.why_empty).empty();
  const std::string picture = prefix + maps::mapExtension(format), tif = prefix + ".tif";
  if (!overwrite && std::filesystem::exists(picture))
    return (error = picture + " exists (not overwritten)").empty();
  if (!maps::writeGeoTiff(tif, map.residual, crs_wkt, error, overwrite))
    return false;
  return map.drawing.write(picture, format, error, overwrite);
}

}  // namespace deformation
}  // namespace pcl_ls3d
