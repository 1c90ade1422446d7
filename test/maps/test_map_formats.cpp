// Maps as files (maps/drawing.h, map_format.h): a PNG is the rasterised drawing with each cell
// in its colour and the colour bar's end colours; a PDF is one page of the map's size whose text
// (read back through the fonts' Unicode maps) holds every label; an SVG is well-formed XML of the
// map's size with a glyph for every character drawn; outlines surround exactly the marked cells;
// unwritable and existing files are refused with one line and nothing left behind.
#include "maps/vector_files.h"

#include <pcl_ls3d/maps/drawing.h>
#include <pcl_ls3d/maps/map_rendering.h>
#include <pcl_ls3d/maps/png_io.h>

#include <gtest/gtest.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <unistd.h>

using namespace pcl_ls3d::maps;
namespace fs = std::filesystem;
using pcl_ls3d_test::pdfText;
using pcl_ls3d_test::slurpBytes;
using pcl_ls3d_test::wellFormedXml;

namespace {

struct Scratch
{
  fs::path dir = fs::temp_directory_path() / ("pcl_ls3d_map_formats_" + std::to_string(::getpid()));
  Scratch()
  {
    fs::create_directories(dir);
  }
  ~Scratch()
  {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string
  file(const std::string& name) const
  {
    return (dir / name).string();
  }
};

// 10 × 5 cells of 1 m, value (col − 4.5) / 4.5 ∈ [−1, 1]; cell (2, 1) has no value.
Raster
rampRaster()
{
  GridGeometry g;
  g.max_y = 5.0;
  g.cols = 10;
  g.rows = 5;
  Raster r(g);
  for (int y = 0; y < r.grid.rows; ++y)
    for (int x = 0; x < r.grid.cols; ++x)
      r.at(x, y) = static_cast<float>((x - 4.5) / 4.5);
  r.at(2, 1) = NAN;
  return r;
}

// A map at 20 pixels per cell with every kind of text.
MapStyle
rampStyle()
{
  MapStyle style;
  style.title = "Overlap 1\u20132: normal discrepancy";
  style.subtitle = {"n = 50   RMS 0.58 m"};
  style.legend = {"|d| < 0.10 m: within tolerance", "positive: 1 above 2"};
  style.footer = "cell 1 m   E 0.0\u201310.0";
  style.max_width = 200;
  style.max_height = 100;
  return style;
}

// The strings rampStyle()'s map draws, besides its tick labels.
std::vector<std::string>
rampTexts(const MapStyle& s)
{
  std::vector<std::string> t = {s.title,   s.subtitle[0], s.legend[0], s.legend[1], s.footer,
                                "no data", "N",           s.unit,      "0",         "2 m"};
  for (const char* tick : {"\u2264 \u22121.00", "\u22120.50", "0.00", "+0.50", "\u2265 +1.00"})
    t.push_back(tick);
  return t;
}

std::size_t
codePoints(const std::string& s, bool count_spaces)
{
  std::size_t n = 0;
  for (unsigned char c : s)
    n += (c & 0xC0) != 0x80 && (count_spaces || c != ' ');
  return n;
}

// First row (from the top) at column x whose pixel is `c`, or −1.
int
firstRowOf(const Image& img, int x, Rgb c)
{
  for (int y = 0; y < img.height(); ++y)
    if (img.get(x, y) == c)
      return y;
  return -1;
}

bool
near(Rgb a, Rgb b, int tolerance)
{
  return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance &&
         std::abs(a.b - b.b) <= tolerance;
}

}  // namespace

TEST(MapFormat, ParsesTheThreeNamesOnly)
{
  MapFormat f = MapFormat::PNG;
  ASSERT_TRUE(parseMapFormat("svg", f));
  EXPECT_EQ(f, MapFormat::SVG);
  ASSERT_TRUE(parseMapFormat("pdf", f));
  EXPECT_EQ(f, MapFormat::PDF);
  ASSERT_TRUE(parseMapFormat("png", f));
  EXPECT_EQ(f, MapFormat::PNG);
  for (const char* bad : {"", "PNG", "jpg", "pdf ", "tif"})
    EXPECT_FALSE(parseMapFormat(bad, f)) << bad;
  EXPECT_EQ(f, MapFormat::PNG);
  EXPECT_EQ(mapExtension(MapFormat::PDF), ".pdf");
  EXPECT_EQ(mapFormatName(MapFormat::SVG), "svg");
}

// Whole-pixel rectangles and frames are drawn in exactly their colour, and the PNG file holds
// the rasterised drawing pixel for pixel.
TEST(Drawing, PngFileIsTheRasterisedDrawing)
{
  const Scratch s;
  Drawing d(40, 30, {255, 255, 255});
  d.fillRect(5, 6, 10, 4, {10, 200, 30});
  d.frame(20, 2, 8, 8, {0, 0, 255});
  const Image img = d.rasterise();
  ASSERT_EQ(img.width(), 40);
  ASSERT_EQ(img.height(), 30);
  EXPECT_EQ(img.get(5, 6), (Rgb{10, 200, 30}));
  EXPECT_EQ(img.get(14, 9), (Rgb{10, 200, 30}));
  EXPECT_EQ(img.get(15, 9), (Rgb{255, 255, 255}));
  EXPECT_EQ(img.get(4, 6), (Rgb{255, 255, 255}));
  EXPECT_EQ(img.get(20, 2), (Rgb{0, 0, 255}));
  EXPECT_EQ(img.get(27, 9), (Rgb{0, 0, 255}));
  EXPECT_EQ(img.get(24, 5), (Rgb{255, 255, 255}));  // inside the frame
  std::string error;
  ASSERT_TRUE(d.write(s.file("d.png"), MapFormat::PNG, error)) << error;
  Image back;
  ASSERT_TRUE(readPng(s.file("d.png"), back, error)) << error;
  EXPECT_EQ(back.width(), 40);
  EXPECT_EQ(back.height(), 30);
  EXPECT_TRUE(back.pixels() == img.pixels());
}

// The PNG of a map shows every cell in its colour at its place (20 × 20 pixels per cell), the
// empty cell in the no-data grey, and the colour bar from the ramp's top colour (dark red,
// +1) down to its bottom colour (dark blue, −1).
TEST(RasterMap, PngShowsEveryCellAndTheColourBarEnds)
{
  const Raster r = rampRaster();
  const ColourMap colours = ColourMap::diverging(1.0);
  const MapStyle style = rampStyle();
  const Image img = renderRasterMap(r, colours, style).rasterise();
  ASSERT_FALSE(img.empty());
  const int x0 = 16, y0 = firstRowOf(img, x0 + 10, colours.colour(r.at(0, 0)));
  ASSERT_GT(y0, 16);
  for (int row = 0; row < r.grid.rows; ++row)
    for (int col = 0; col < r.grid.cols; ++col) {
      const Rgb expected = std::isfinite(r.at(col, row)) ? colours.colour(r.at(col, row)) : style.no_data;
      for (const auto& [dx, dy] : {std::pair{1, 1}, std::pair{10, 10}, std::pair{18, 18}})
        EXPECT_EQ(img.get(x0 + 20 * col + dx, y0 + 20 * row + dy), expected) << col << ", " << row;
    }
  EXPECT_EQ(img.get(x0 - 1, y0 + 10), (Rgb{90, 90, 90}));  // the map's frame
  const int bar_x = x0 + 10 * 20 + 24 + 10;
  int top = -1, bottom = -1;
  for (int y = 0; y < img.height(); ++y) {
    if (top < 0 && near(img.get(bar_x, y), colours.colour(1.0), 3))
      top = y;
    if (near(img.get(bar_x, y), colours.colour(-1.0), 3))
      bottom = y;
  }
  ASSERT_GE(top, 0) << "no dark red in the colour bar";
  ASSERT_GE(bottom, 0) << "no dark blue in the colour bar";
  EXPECT_GE(bottom - top, 150);                           // the bar is at least 160 pixels high
  EXPECT_EQ(img.get(bar_x, top - 1), (Rgb{90, 90, 90}));  // the bar's frame right above red
}

// A PDF map is one page of the drawing's size at 96 dpi whose text holds every label drawn.
TEST(RasterMap, PdfIsOnePageWithEveryLabel)
{
  const Scratch s;
  const MapStyle style = rampStyle();
  const Drawing d = renderRasterMap(rampRaster(), ColourMap::diverging(1.0), style);
  std::string error;
  ASSERT_TRUE(d.write(s.file("map.pdf"), MapFormat::PDF, error)) << error;
  const std::string pdf = slurpBytes(s.file("map.pdf"));
  ASSERT_EQ(pdf.compare(0, 5, "%PDF-"), 0);
  const std::regex page(R"(/Type\s*/Page[^s])"), box(R"(/MediaBox\s*\[\s*0 0 ([\d.]+) ([\d.]+)\s*\])");
  EXPECT_EQ(std::distance(std::sregex_iterator(pdf.begin(), pdf.end(), page), std::sregex_iterator()), 1);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(pdf, m, box));
  EXPECT_NEAR(std::stod(m[1]), 0.75 * d.width(), 0.01);
  EXPECT_NEAR(std::stod(m[2]), 0.75 * d.height(), 0.01);
  std::string text;
  for (const std::string& t : pdfText(pdf))
    text += t;
  for (const std::string& label : rampTexts(style))
    EXPECT_NE(text.find(label), std::string::npos) << "'" << label << "' not in: " << text;
}

// An SVG map is well-formed XML sized in pixels, with the cells embedded as an image and one
// glyph for each character drawn (cairo draws text as glyph outlines).
TEST(RasterMap, SvgIsWellFormedWithAGlyphPerCharacter)
{
  const Scratch s;
  const MapStyle style = rampStyle();
  const Drawing d = renderRasterMap(rampRaster(), ColourMap::diverging(1.0), style);
  std::string error;
  ASSERT_TRUE(d.write(s.file("map.svg"), MapFormat::SVG, error)) << error;
  const std::string svg = slurpBytes(s.file("map.svg"));
  std::string why;
  EXPECT_TRUE(wellFormedXml(svg, why)) << why;
  EXPECT_NE(svg.find("width=\"" + std::to_string(d.width()) + "px\""), std::string::npos);
  EXPECT_NE(svg.find("height=\"" + std::to_string(d.height()) + "px\""), std::string::npos);
  EXPECT_NE(svg.find("<image"), std::string::npos);
  const std::regex use(R"(<use xlink:href="#glyph)");
  const auto glyphs = static_cast<std::size_t>(
      std::distance(std::sregex_iterator(svg.begin(), svg.end(), use), std::sregex_iterator()));
  std::size_t visible = 0, all = 0;
  for (const std::string& t : rampTexts(style)) {
    visible += codePoints(t, false);
    all += codePoints(t, true);
  }
  EXPECT_GE(glyphs, visible);
  EXPECT_LE(glyphs, all);
}

// Marked cells are outlined on their border pixels (two pixels wide at 20 pixels per cell) and
// only there; without marks no pixel has the outline's colour.
TEST(RasterMap, OutlineSurroundsTheMarkedCells)
{
  const Raster r = rampRaster();
  Raster marked(r.grid);
  for (int y = 0; y < r.grid.rows; ++y)
    for (int x = 0; x < r.grid.cols; ++x)
      marked.at(x, y) = x >= 6 && x < 9 && y >= 1 && y < 3 ? 1.0f : 0.0f;
  const ColourMap colours = ColourMap::diverging(1.0);
  const Image plain = renderRasterMap(r, colours, rampStyle()).rasterise();
  const Image img = renderRasterMap(r, colours, rampStyle(), &marked).rasterise();
  const int x0 = 16, y0 = firstRowOf(img, x0 + 10, colours.colour(r.at(0, 0)));
  ASSERT_GT(y0, 16);
  std::size_t outline = 0, plain_outline = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      outline += img.get(x, y) == kOutlineColour;
      plain_outline += plain.get(x, y) == kOutlineColour;
    }
  EXPECT_EQ(plain_outline, 0u);
  // A ring two pixels wide just inside the 60 × 40 pixels of the block: 60 × 40 − 56 × 36 = 384.
  EXPECT_EQ(outline, 384u);
  EXPECT_EQ(img.get(x0 + 120, y0 + 20), kOutlineColour);  // the block's top left pixel
  EXPECT_EQ(img.get(x0 + 121, y0 + 21), kOutlineColour);
  EXPECT_EQ(img.get(x0 + 179, y0 + 59), kOutlineColour);              // its bottom right pixel
  EXPECT_EQ(img.get(x0 + 122, y0 + 22), colours.colour(r.at(6, 1)));  // the cell inside
  EXPECT_EQ(img.get(x0 + 119, y0 + 20), colours.colour(r.at(5, 1)));  // the cell left of it
  EXPECT_EQ(img.get(x0 + 120, y0 + 19), colours.colour(r.at(6, 0)));  // the cell above it
}

// A histogram's PDF holds its title, axis label and both series' labels.
TEST(Histogram, PdfHoldsTitleAxisAndLegend)
{
  const Scratch s;
  HistogramSeries before{"before: RMS 0.150 m", {}, {214, 96, 77}},
      after{"after: RMS 0.030 m", {}, {33, 102, 172}};
  for (int i = -50; i <= 50; ++i) {
    before.values.push_back(0.003 * i);
    after.values.push_back(0.0006 * i);
  }
  HistogramStyle style;
  style.title = "All overlaps: discrepancies before and after adjustment";
  const Drawing d = renderHistogram({before, after}, style);
  std::string error;
  ASSERT_TRUE(d.write(s.file("h.pdf"), MapFormat::PDF, error)) << error;
  std::string text;
  for (const std::string& t : pdfText(slurpBytes(s.file("h.pdf"))))
    text += t;
  for (const std::string& label : {style.title, style.x_label, before.label, after.label})
    EXPECT_NE(text.find(label), std::string::npos) << "'" << label << "' not in: " << text;
}

// Every format refuses a path it cannot write and an existing file (kept unchanged) with one
// line, and leaves no file behind; overwrite replaces.
TEST(Drawing, RefusesUnwritableAndExistingFiles)
{
  const Scratch s;
  Drawing d(20, 10);
  d.setTitle("Test map");
  for (MapFormat f : {MapFormat::PNG, MapFormat::PDF, MapFormat::SVG}) {
    const std::string ext = mapExtension(f);
    std::string error;
    EXPECT_FALSE(d.write(s.file("missing_dir/m" + ext), f, error));
    EXPECT_EQ(error.rfind("cannot write ", 0), 0u) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_FALSE(fs::exists(s.file("missing_dir")));
    const std::string path = s.file("m" + ext);
    {
      std::ofstream(path) << "keep";
    }
    EXPECT_FALSE(d.write(path, f, error));
    EXPECT_NE(error.find("exists"), std::string::npos) << error;
    EXPECT_EQ(slurpBytes(path), "keep");
    ASSERT_TRUE(d.write(path, f, error, true)) << error;
    EXPECT_NE(slurpBytes(path), "keep");
    EXPECT_FALSE(Drawing().write(s.file("empty" + ext), f, error));
    EXPECT_FALSE(fs::exists(s.file("empty" + ext)));
  }
  EXPECT_NE(slurpBytes(s.file("m.pdf")).find("/Title (Test map)"), std::string::npos);
}

// A write that fails on the way (a full disk: /dev/full) is reported with the system's reason;
// the device written to is not removed as a partial file would be.
TEST(Drawing, FullDiskIsReportedAndTheDeviceKept)
{
  if (!fs::exists("/dev/full"))
    GTEST_SKIP() << "no /dev/full on this system";
  Drawing d(300, 200);
  d.text(10, 20, "a map that does not fit", {0, 0, 0});
  for (MapFormat f : {MapFormat::PNG, MapFormat::PDF, MapFormat::SVG}) {
    std::string error;
    EXPECT_FALSE(d.write("/dev/full", f, error, true)) << mapFormatName(f);
    EXPECT_EQ(error, "cannot write /dev/full: " + std::string(std::strerror(ENOSPC))) << mapFormatName(f);
    EXPECT_TRUE(fs::exists("/dev/full"));
  }
  std::string error;
  EXPECT_FALSE(writePng("/dev/full", d.rasterise(), error));
  EXPECT_TRUE(fs::exists("/dev/full"));
}
