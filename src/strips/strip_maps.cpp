// Discrepancy maps of a strip adjustment (strip_maps.h).
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/maps/geotiff_io.h>
#include <pcl_ls3d/maps/map_rendering.h>
#include <pcl_ls3d/strips/strip_maps.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace pcl_ls3d {
namespace strips {

namespace fs = std::filesystem;

namespace {

struct Units
{
  double per_metre = 1.0;  // data units per metre
  std::string name = "m";
};

Units
unitsOf(const std::string& wkt)
{
  Units u;
  const double metres = maps::crsLinearUnit(wkt);
  if (!(metres > 0.0))
    u.name = "input units";  // no CRS: the bands are taken in the input's own unit
  else if (std::abs(metres - 1.0) > 1e-9) {
    u.per_metre = 1.0 / metres;
    u.name = maps::crsLinearUnitName(wkt);
  }
  return u;
}

std::string
fmt(const char* f, double v)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), f, v);
  return buf;
}

std::string
statsLine(const DiscrepancyStatistics& s, const std::string& unit)
{
  char buf[256];
  std::snprintf(
      buf, sizeof(buf),
      "n = %zu   mean %+.3f %s   RMS %.3f %s   \u03c3MAD %.3f %s   5\u201395 %%: %+.3f \u2026 %+.3f %s",
      s.count, s.mean, unit.c_str(), s.rms, unit.c_str(), s.sigma_mad, unit.c_str(), s.p05, s.p95,
      unit.c_str());
  return buf;
}

maps::Raster
rasterOf(const DiscrepancySamples& s, const maps::GridGeometry& grid, const Eigen::Vector3d& origin)
{
  maps::RasterAccumulator acc(grid);
  for (std::size_t k = 0; k < s.value.size(); ++k)
    acc.add(s.xy[k].x() + origin.x(), s.xy[k].y() + origin.y(), s.value[k]);
  return acc.result();
}

maps::GridGeometry
gridOf(const std::vector<const DiscrepancySamples*>& sets, const Eigen::Vector3d& origin, double cell)
{
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const DiscrepancySamples* s : sets)
    for (const auto& xy : s->xy) {
      lo = lo.cwiseMin(xy + origin.head<2>());
      hi = hi.cwiseMax(xy + origin.head<2>());
    }
  return lo.allFinite() ? maps::GridGeometry::covering(lo, hi, cell) : maps::GridGeometry();
}

class MapWriter
{
public:
  MapWriter(const std::string& dir, const StripMapSettings& settings, std::vector<std::string>& written)
      : dir_(dir), settings_(settings), written_(written), units_(unitsOf(settings.crs_wkt)),
        colours_(maps::ColourMap::bandedDiverging(settings.inner * units_.per_metre,
                                                  settings.outer * units_.per_metre))
  {}

  bool
  raster(const std::string& stem, const maps::Raster& r, const std::string& title,
         const std::vector<std::string>& subtitle, const std::string& sign, std::string& error)
  {
    if (settings_.geotiff && !maps::writeGeoTiff(path(stem + ".tif"), r, settings_.crs_wkt, error))
      return false;
    if (settings_.geotiff)
      written_.push_back(path(stem + ".tif"));
    if (!settings_.pictures)
      return true;
    maps::MapStyle style;
    style.title = title;
    style.subtitle = subtitle;
    style.unit = units_.name;
    style.tick_format = "%+.2f";
    style.length_unit = units_.name;
    const double i = settings_.inner * units_.per_metre, o = settings_.outer * units_.per_metre;
    style.legend = {"|d| < " + fmt("%.2f", i) + " " + units_.name + ": within tolerance",
                    fmt("%.2f", i) + "\u2013" + fmt("%.2f", o) + " " + units_.name + ": check",
                    "> " + fmt("%.2f", o) + " " + units_.name + ": exceeds", sign};
    const std::string crs = maps::crsName(settings_.crs_wkt);
    char foot[256];
    std::snprintf(foot, sizeof(foot), "cell %.3g %s   E %.1f\u2013%.1f   N %.1f\u2013%.1f   %s", r.grid.cell,
                  units_.name.c_str(), r.grid.min_x, r.grid.maxX(), r.grid.minY(), r.grid.max_y,
                  crs.empty() ? "no CRS in the input" : crs.c_str());
    style.footer = foot;
    return picture(stem, maps::renderRasterMap(r, colours_, style), error);
  }

  bool
  picture(const std::string& stem, const maps::Drawing& drawing, std::string& error)
  {
    const std::string file = path(stem + maps::mapExtension(settings_.format));
    if (!drawing.write(file, settings_.format, error))
      return false;
    written_.push_back(file);
    return true;
  }

  const Units&
  units() const
  {
    return units_;
  }

private:
  std::string
  path(const std::string& name) const
  {
    return (fs::path(dir_) / name).string();
  }
  std::string dir_;
  const StripMapSettings& settings_;
  std::vector<std::string>& written_;
  Units units_;
  maps::ColourMap colours_;
};

bool
histogram(MapWriter& w, const std::string& stem, const std::string& title, const std::vector<float>& before,
          const std::vector<float>& after, const StripMapSettings& settings, std::string& error)
{
  const DiscrepancyStatistics sb = discrepancyStatistics(before), sa = discrepancyStatistics(after);
  const std::string u = w.units().name;
  maps::HistogramSeries b{"before: RMS " + fmt("%.3f", sb.rms) + " " + u + ", \u03c3MAD " +
                              fmt("%.3f", sb.sigma_mad) + " " + u,
                          std::vector<double>(before.begin(), before.end()),
                          {214, 96, 77}};
  maps::HistogramSeries a{"after: RMS " + fmt("%.3f", sa.rms) + " " + u + ", \u03c3MAD " +
                              fmt("%.3f", sa.sigma_mad) + " " + u,
                          std::vector<double>(after.begin(), after.end()),
                          {33, 102, 172}};
  maps::HistogramStyle style;
  style.title = title;
  style.x_label = "signed normal discrepancy [" + u + "]";
  const double i = settings.inner * w.units().per_metre, o = settings.outer * w.units().per_metre;
  style.marks = {-o, -i, i, o};
  return settings.pictures ? w.picture(stem, maps::renderHistogram({b, a}, style), error) : true;
}

}  // namespace

bool
writeStripMaps(const StripAdjustmentReport& report, const StripPlan& plan,
               const std::vector<OverlapSamples>& samples, const std::string& dir,
               const StripMapSettings& settings, std::vector<std::string>& written, std::string& error)
{
  MapWriter w(dir, settings, written);
  const Eigen::Vector3d& origin = plan.block_origin;
  std::vector<float> all_before, all_after;
  double mosaic_cell = settings.cell;
  for (std::size_t k = 0; k < report.overlaps.size() && k < samples.size(); ++k) {
    const OverlapResult& o = report.overlaps[k];
    if (!o.used || samples[k].before.value.empty())
      continue;
    const std::string a = report.strips[static_cast<std::size_t>(o.i)].name,
                      b = report.strips[static_cast<std::size_t>(o.j)].name;
    const double cell = settings.cell > 0.0 ? settings.cell : 2.0 * o.spacing;
    mosaic_cell = std::max(mosaic_cell, cell);
    const maps::GridGeometry grid = gridOf({&samples[k].before, &samples[k].after}, origin, cell);
    const maps::Raster before = rasterOf(samples[k].before, grid, origin);
    const maps::Raster after = rasterOf(samples[k].after, grid, origin);
    const std::string sign = "positive: " + a + " above " + b;
    const std::string stem = "overlap_" + a + "_" + b;
    if (!w.raster(stem + "_before", before,
                  "Overlap " + a + " \u2013 " + b + ": normal discrepancy before adjustment",
                  {statsLine(o.before, w.units().name)}, sign, error) ||
        !w.raster(stem + "_after", after,
                  "Overlap " + a + " \u2013 " + b + ": normal discrepancy after adjustment",
                  {statsLine(o.after, w.units().name)}, sign, error) ||
        !histogram(w, stem + "_histogram",
                   "Overlap " + a + " \u2013 " + b + ": discrepancies before and after",
                   samples[k].before.value, samples[k].after.value, settings, error))
      return false;
    all_before.insert(all_before.end(), samples[k].before.value.begin(), samples[k].before.value.end());
    all_after.insert(all_after.end(), samples[k].after.value.begin(), samples[k].after.value.end());
  }
  // Mosaic of all overlaps: per cell the value of largest magnitude (the conservative view
  // where several overlaps meet). Each overlap is rasterised on its own grid of the mosaic's
  // cell (grids snap to multiples of the cell, so their cells coincide).
  std::vector<const DiscrepancySamples*> sets;
  for (const OverlapSamples& s : samples) {
    sets.push_back(&s.before);
    sets.push_back(&s.after);
  }
  const double cell = mosaic_cell > 0.0 ? mosaic_cell : 1.0;
  const maps::GridGeometry grid = gridOf(sets, origin, cell);
  if (!grid.valid())
    return true;
  for (int phase = 0; phase < 2; ++phase) {
    maps::RasterAccumulator worst(grid, maps::RasterAccumulator::Mode::MAX_ABS);
    for (const OverlapSamples& os : samples) {
      const DiscrepancySamples& s = phase == 0 ? os.before : os.after;
      if (!s.value.empty())
        worst.addRaster(rasterOf(s, gridOf({&s}, origin, cell), origin));
    }
    const char* when = phase == 0 ? "before" : "after";
    const DiscrepancyStatistics st = discrepancyStatistics(phase == 0 ? all_before : all_after);
    if (!w.raster(std::string("mosaic_") + when, worst.result(),
                  std::string("All overlaps: normal discrepancy ") + when + " adjustment",
                  {statsLine(st, w.units().name), "per cell the overlap with the largest |d|"},
                  "positive: lower-numbered strip above", error))
      return false;
  }
  return histogram(w, "histogram", "All overlaps: discrepancies before and after adjustment", all_before,
                   all_after, settings, error);
}

}  // namespace strips
}  // namespace pcl_ls3d
