// Map images (maps/map_rendering.h, drawing.h, png_io.h): what is drawn can be read back from the
// PNG pixel for pixel; a discrepancy map shows each class in its colour, the no-data grey, a
// colour bar with its class boundaries and text; histograms show both series.
#include <pcl_ls3d/maps/map_rendering.h>
#include <pcl_ls3d/maps/png_io.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <set>

using namespace pcl_ls3d::maps;

namespace {

std::string
tempPath(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("pcl_ls3d_maps_" + name)).string();
}

std::size_t
countColour(const Image& img, Rgb c, int x0 = 0, int y0 = 0, int x1 = -1, int y1 = -1)
{
  if (x1 < 0)
    x1 = img.width();
  if (y1 < 0)
    y1 = img.height();
  std::size_t n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      n += img.get(x, y) == c;
  return n;
}

std::size_t
countDark(const Image& img, int x0, int y0, int x1, int y1)
{
  std::size_t n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const Rgb c = img.get(x, y);
      n += c.r + c.g + c.b < 200;
    }
  return n;
}

}  // namespace

TEST(Image, TextIsDrawnAndMeasured)
{
  Drawing drawing(200, 40);
  const double w = drawing.text(10, 25, "\u03c3 = 0.10 m \u00b1", {0, 0, 0});
  EXPECT_EQ(w, Drawing::textWidth("\u03c3 = 0.10 m \u00b1"));
  EXPECT_GT(w, 40);
  const Image img = drawing.rasterise();
  const int end = static_cast<int>(std::ceil(10 + w));
  EXPECT_GT(countDark(img, 10, 10, end, 30), 30u);
  EXPECT_EQ(countDark(img, end + 2, 0, 200, 40), 0u);
  // Bytes that are no UTF-8 become '?', not nothing (cairo would refuse the whole text).
  EXPECT_EQ(Drawing::textWidth("\xff"), Drawing::textWidth("?"));
  EXPECT_EQ(Drawing::textWidth("a\xc3"
                               "b"),
            Drawing::textWidth("a?b"));  // truncated sequence
  EXPECT_GT(Drawing::lineHeight(FontStyle::BOLD), Drawing::lineHeight());
}

TEST(PngIo, WrittenPixelsReadBackExactly)
{
  Image img(37, 23);
  std::mt19937 rng(3);
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      img.set(x, y,
              {static_cast<std::uint8_t>(rng()), static_cast<std::uint8_t>(rng()),
               static_cast<std::uint8_t>(rng())});
  const std::string path = tempPath("roundtrip.png");
  std::string error;
  ASSERT_TRUE(writePng(path, img, error)) << error;
  Image back;
  ASSERT_TRUE(readPng(path, back, error)) << error;
  ASSERT_EQ(back.width(), 37);
  ASSERT_EQ(back.height(), 23);
  EXPECT_EQ(back.pixels(), img.pixels());
  std::remove(path.c_str());
  EXPECT_FALSE(writePng("/nonexistent_dir/x.png", img, error));
  EXPECT_FALSE(error.empty());
  EXPECT_FALSE(readPng(tempPath("missing.png"), back, error));
}

TEST(RasterMap, ShowsEveryClassTheNoDataGreyAndALegend)
{
  Raster r(GridGeometry::covering({0, 0}, {39.9, 19.9}, 1.0));  // 40 × 20 cells
  for (int y = 0; y < r.grid.rows; ++y)
    for (int x = 0; x < r.grid.cols; ++x)
      r.at(x, y) = x < 10 ? -0.25f : x < 20 ? -0.05f : x < 30 ? 0.15f : 0.25f;
  r.at(5, 5) = NAN;
  const ColourMap cmap = ColourMap::bandedDiverging();
  MapStyle style;
  style.title = "Overlap 1\u20132 before adjustment";
  style.subtitle = {"n = 800  RMS 0.180 m"};
  style.legend = {"|d| < 0.10 m: within tolerance"};
  style.footer = "cell 1 m";
  const Image img = renderRasterMap(r, cmap, style).rasterise();
  ASSERT_FALSE(img.empty());
  // 40 cells fit 760 px 19 times: each cell is a 19 × 19 block.
  for (float v : {-0.25f, -0.05f, 0.15f, 0.25f})
    EXPECT_GE(countColour(img, cmap.colour(v)), 10u * 20u * 19u * 19u - 19u * 19u) << v;
  EXPECT_GE(countColour(img, style.no_data), 19u * 19u);
  // Title text is drawn in the top band.
  EXPECT_GT(countDark(img, 0, 0, img.width(), 30), 50u);
  // The colour bar (a 20-pixel column right of the map) runs from dark red (RdBu ends at
  // 103,0,31) to dark blue through white.
  const int bar_x = 16 + 40 * 19 + 24;
  std::size_t red = 0, blue = 0, white = 0;
  for (int y = 0; y < img.height(); ++y) {
    const Rgb c = img.get(bar_x + 10, y);
    red += c.r > 95 && c.g < 60 && c.b < 80;
    blue += c.b > 90 && c.r < 60 && c.g < 110;
    white += c.r > 240 && c.g > 240 && c.b > 240;
  }
  EXPECT_GT(red, 30u);
  EXPECT_GT(blue, 30u);
  EXPECT_GT(white, 10u);
  const std::string path = tempPath("map.png");
  std::string error;
  ASSERT_TRUE(writePng(path, img, error)) << error;
  std::remove(path.c_str());
}

TEST(RasterMap, LargeRastersAreAveragedDownToTheMapArea)
{
  Raster r(GridGeometry::covering({0, 0}, {1999.5, 999.5}, 1.0));
  for (std::size_t k = 0; k < r.values.size(); ++k)
    r.values[k] = 0.25f;
  MapStyle style;
  const Image img = renderRasterMap(r, ColourMap::bandedDiverging(), style).rasterise();
  ASSERT_FALSE(img.empty());
  EXPECT_LE(img.width(), 760 + 400);
  EXPECT_GE(countColour(img, ColourMap::bandedDiverging().colour(0.25)), 700u * 350u);
}

TEST(Histogram, BothSeriesAreVisible)
{
  std::mt19937 rng(1);
  std::normal_distribution<double> wide(0.05, 0.15), narrow(0.0, 0.03);
  HistogramSeries before{"before", {}, {214, 96, 77}}, after{"after", {}, {33, 102, 172}};
  for (int i = 0; i < 5000; ++i) {
    before.values.push_back(wide(rng));
    after.values.push_back(narrow(rng));
  }
  HistogramStyle style;
  style.title = "Normal discrepancies";
  style.marks = {-0.2, -0.1, 0.1, 0.2};
  const Image img = renderHistogram({before, after}, style).rasterise();
  ASSERT_FALSE(img.empty());
  EXPECT_GT(countColour(img, before.colour), 200u);
  EXPECT_GT(countColour(img, after.colour), 200u);
  EXPECT_DOUBLE_EQ(niceStep(10.0, 5), 2.0);
  EXPECT_DOUBLE_EQ(niceStep(0.7, 4), 0.2);
}
