// The deformation map on Li's surface with a planted patch of known extent and height: the
// residual raster shows the patch at its height and the stable part at zero, the region raster
// covers the patch's area, the outline is drawn only when there are regions, and the files read
// back: the PNG pixel for pixel, the GeoTIFF value for value with the CRS it was given.
#include <pcl_ls3d/deformation/deformation_map.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/maps/geotiff_io.h>
#include <pcl_ls3d/maps/png_io.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/synth/li_surface.h>

#include <pcl/search/kdtree.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unistd.h>

using namespace pcl_ls3d;
using namespace pcl_ls3d::deformation;
namespace fs = std::filesystem;

namespace {

constexpr double kSigma = 20.0, kC = 10.0;

struct Analysed
{
  synth::LiSurface li;
  std::vector<Eigen::Vector3d> points;
  DeformationResult result;
};

/// 20 % of Li's surface raised by N(10 σ, σ) at the lower right, analysed with the defaults.
const Analysed&
analysed()
{
  static const Analysed a = [] {
    Analysed out;
    synth::LiSurfaceSettings ls;
    ls.deformation_percent = 20.0;
    ls.deformation_c = kC;
    ls.position = synth::DeformationPosition::LOWER_RIGHT;
    out.li = synth::makeLiSurface(ls);
    for (const auto& p : *out.li.mate)
      out.points.push_back(p.getVector3fMap().cast<double>());
    pcl::search::KdTree<PointLiDAR>::Ptr tree(new pcl::search::KdTree<PointLiDAR>);
    tree->setInputCloud(out.li.reference);
    const PclTargetSurface<PointLiDAR> surface(out.li.reference, tree);
    const ConjugateRule::Ptr rule = makeConjugateRule(ConjugateRuleType::LZD);
    std::string why;
    rule->prepare(surface, &why);
    out.result = analyseDeformation(out.points, surface, *rule, DeformationSettings());
    return out;
  }();
  return a;
}

std::size_t
darkPixels(const maps::Image& img)
{
  std::size_t n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      n += img.get(x, y) == maps::Rgb{20, 20, 20};
  return n;
}

}  // namespace

TEST(DeformationMap, RastersShowThePlantedPatch)
{
  const Analysed& a = analysed();
  ASSERT_TRUE(a.result.ok());
  const DeformationMap map = makeDeformationMap(a.points, a.result, DeformationMapSettings());
  ASSERT_FALSE(map.drawing.empty());
  ASSERT_EQ(map.residual.values.size(), map.in_region.values.size());
  // Cells of the region hold the patch's height, the others the stable surface's zero.
  double in_sum = 0.0, out_sum = 0.0;
  std::size_t in_n = 0, out_n = 0;
  for (std::size_t i = 0; i < map.residual.values.size(); ++i) {
    const float v = map.residual.values[i];
    if (!std::isfinite(v))
      continue;
    if (map.in_region.values[i] > 0.5f) {
      in_sum += v;
      ++in_n;
    } else {
      out_sum += v;
      ++out_n;
    }
  }
  ASSERT_GT(in_n, 0u);
  ASSERT_GT(out_n, 0u);
  EXPECT_NEAR(in_sum / static_cast<double>(in_n), kC * kSigma, 2.0 * kSigma);
  EXPECT_NEAR(out_sum / static_cast<double>(out_n), 0.0, 0.5 * kSigma);
  // The region cells cover the planted area (20 % of the 4900 × 4900 surface; cells of 1.5
  // spacings overlap the patch's border, hence the tolerance).
  const double cell_area = map.residual.grid.cell * map.residual.grid.cell;
  const double planted = a.li.percent / 100.0 * 4900.0 * 4900.0;
  EXPECT_NEAR(static_cast<double>(in_n) * cell_area / planted, 1.0, 0.3);
  // The colour range holds the patch and the significance threshold.
  EXPECT_GE(map.limit, 2.0 * 3.0 * a.result.matching.scale);
}

TEST(DeformationMap, RegionsAreOutlinedOnlyWhenThereAreRegions)
{
  const Analysed& a = analysed();
  ASSERT_TRUE(a.result.ok());
  const DeformationMap map = makeDeformationMap(a.points, a.result, DeformationMapSettings());
  DeformationResult none = a.result;
  std::fill(none.regions.region.begin(), none.regions.region.end(), 0);
  const DeformationMap plain = makeDeformationMap(a.points, none, DeformationMapSettings());
  ASSERT_EQ(plain.drawing.width(), map.drawing.width());
  ASSERT_EQ(plain.drawing.height(), map.drawing.height());
  EXPECT_EQ(darkPixels(plain.drawing.rasterise()), 0u);
  // A closed outline two pixels wide around a patch of about 2000 × 2000 units.
  EXPECT_GT(darkPixels(map.drawing.rasterise()), 200u);
}

TEST(DeformationMap, FilesReadBackWithTheirCrs)
{
  const Analysed& a = analysed();
  ASSERT_TRUE(a.result.ok());
  const fs::path dir = fs::temp_directory_path() / ("pcl_ls3d_deformation_map_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string prefix = (dir / "map").string();
  const std::string crs = maps::crsFromUserInput("EPSG:26917");
  ASSERT_FALSE(crs.empty());
  DeformationMapSettings s;
  s.crs_wkt = crs;
  s.origin = Eigen::Vector3d(634000.0, 4831000.0, 0.0);
  const DeformationMap map = makeDeformationMap(a.points, a.result, s);
  std::string error;
  ASSERT_TRUE(writeDeformationMap(prefix, map, crs, false, error)) << error;

  maps::Image png;
  ASSERT_TRUE(maps::readPng(prefix + ".png", png, error)) << error;
  EXPECT_EQ(png.width(), map.drawing.width());
  EXPECT_EQ(png.height(), map.drawing.height());
  EXPECT_TRUE(png.pixels() == map.drawing.rasterise().pixels());

  maps::Raster tif;
  std::string tif_crs;
  ASSERT_TRUE(maps::readGeoTiff(prefix + ".tif", tif, tif_crs, error)) << error;
  EXPECT_TRUE(maps::sameCrs(tif_crs, crs));
  ASSERT_EQ(tif.values.size(), map.residual.values.size());
  EXPECT_DOUBLE_EQ(tif.grid.min_x, map.residual.grid.min_x);
  EXPECT_DOUBLE_EQ(tif.grid.max_y, map.residual.grid.max_y);
  EXPECT_GT(tif.grid.min_x, 630000.0);  // the origin was applied: file coordinates
  for (std::size_t i = 0; i < tif.values.size(); ++i) {
    if (std::isnan(map.residual.values[i]))
      EXPECT_TRUE(std::isnan(tif.values[i])) << i;
    else
      EXPECT_FLOAT_EQ(tif.values[i], map.residual.values[i]) << i;
  }
  // Existing files are kept.
  EXPECT_FALSE(writeDeformationMap(prefix, map, crs, false, error));
  EXPECT_NE(error.find("exists"), std::string::npos) << error;
  std::error_code ec;
  fs::remove_all(dir, ec);
}

// The map's text says in which unit the residuals are: the CRS's length unit over the colour bar
// and after the cell (as the strip maps do), the input's own units when no CRS is known. The
// subtitle keeps the whole estimator description however long, on lines a reader can follow.
TEST(DeformationMap, TextNamesTheUnitAndKeepsTheWholeSubtitle)
{
  const Analysed& a = analysed();
  ASSERT_TRUE(a.result.ok());
  DeformationMapSettings metres;
  metres.crs_wkt = maps::crsFromUserInput("EPSG:26917");  // NAD83 / UTM 17N, metres
  ASSERT_FALSE(metres.crs_wkt.empty());
  const DeformationMap m = makeDeformationMap(a.points, a.result, metres);
  EXPECT_EQ(m.style.unit, "m");
  EXPECT_EQ(m.style.length_unit, "m");
  EXPECT_NE(m.style.footer.find(" m, "), std::string::npos) << m.style.footer;
  EXPECT_NE(m.style.footer.find("UTM zone 17N"), std::string::npos) << m.style.footer;

  DeformationMapSettings feet;
  feet.crs_wkt = maps::crsFromUserInput("EPSG:2263");  // NAD83 / New York Long Island (ftUS)
  ASSERT_FALSE(feet.crs_wkt.empty());
  EXPECT_EQ(makeDeformationMap(a.points, a.result, feet).style.unit, "ft");

  const DeformationMap none = makeDeformationMap(a.points, a.result, DeformationMapSettings());
  EXPECT_EQ(none.style.unit, "input units");
  EXPECT_NE(none.style.footer.find("input units"), std::string::npos) << none.style.footer;
  EXPECT_TRUE(none.style.length_unit.empty());  // no scale bar in unknown units

  DeformationResult long_name = a.result;
  std::string name;
  for (int i = 0; name.size() < 400; ++i)
    name += (i ? " then stage-" : "stage-") + std::to_string(i);
  long_name.matching.estimator = name;
  const DeformationMap wrapped = makeDeformationMap(a.points, long_name, DeformationMapSettings());
  std::string joined;
  for (const std::string& line : wrapped.style.subtitle) {
    EXPECT_LE(line.size(), 120u) << line;
    joined += (joined.empty() ? "" : " ") + line;
  }
  EXPECT_NE(joined.find(name), std::string::npos) << joined;
  EXPECT_NE(joined.find("noise clusters"), std::string::npos) << joined;
}
