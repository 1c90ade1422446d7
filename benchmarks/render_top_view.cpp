/// \file render_top_view.cpp
/// \brief Top-view PNG of a segmented or classified cloud, to look at a segmentation as a user
///        would: each pixel shows the highest point's colour, and pixels whose neighbour shows
///        another segment are darkened so segment borders (and fragmentation) are visible.
///        The picture is framed as a map for people without the software: a margin with a
///        scale bar, a north arrow (top view) or the side view's direction, a legend of the
///        classes shown (class colours) and a one-line caption (segments or classes, points,
///        view, pixel size); -plain writes the picture alone, as before the margin existed.
///
/// Usage: render_top_view INPUT OUT.png|pdf|svg [-pixel m] [-splat n] [-by rgb|label|class]
///                       [-crop x0,x1,y0,y1] [-view top|north|east|south|west] [-plain] [-overwrite]
///   INPUT  SEGMENTS.pcd of pcl_ls3d_segment (x y z rgba label [classification]), or any cloud
///          pcl_ls3d reads (-by class colours by the LAS classification / PCD label with a fixed
///          palette; a SEGMENTS.pcd by its objects' classes, legend with IMRG's class names)
///   -pixel pixel size in cloud units (default 0.25)
///   -splat each point also paints the pixels within n of its own (default 1: 3 × 3)
///   -by    rgb: the file's colours (default; a PCD without rgb/rgba: by label); label: a colour
///          per label (LAS, PLY, XYZ: per class); class: ASPRS palette (ground brown,
///          vegetation greens, building red, wire yellow)
///   -crop  keep only points with x0 ≤ x ≤ x1 and y0 ≤ y ≤ y1 (the file's local coordinates)
///   -view  top (default); or a side view looking north, east, south or west, the nearest
///          point per pixel shown (facades, storeys, what hangs under a roof)
///   -plain the picture alone, without margin (pixel for pixel the map's picture area)
/// Not run by CTest: a viewing aid for docs/BENCHMARKS.md.

#include "../tools/tool_options.h"

#include <pcl_ls3d/evaluation/segmentation_classes.h>
#include <pcl_ls3d/evaluation/segmentation_labels.h>
#include <pcl_ls3d/evaluation/segments_file.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/maps/map_format.h>
#include <pcl_ls3d/maps/map_rendering.h>
#include <pcl_ls3d/maps/png_io.h>
#include <pcl_ls3d/segmentation/object_classes.h>

#include <pcl/console/parse.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace {

struct Sample
{
  float x, y, z;
  std::uint32_t rgb;    ///< 0x00RRGGBB
  std::uint32_t label;  ///< segment or class: borders are drawn between different labels
};

/// ASPRS classes: ground brown, low/medium/high vegetation light to dark green, building red,
/// wire yellow, tower orange, user classes (cars: 64) blue, unclassified grey.
std::uint32_t
classColour(std::uint32_t c)
{
  switch (c) {
  case 2:
    return 0xa0785a;
  case 3:
    return 0x9ad07a;
  case 4:
    return 0x4caf50;
  case 5:
    return 0x1b5e20;
  case 6:
    return 0xd03030;
  case 14:
    return 0xffe000;
  case 15:
    return 0xff8c00;
  case 9:
    return 0x3070ff;
  default:
    return c >= 64 ? 0x2040c0 : 0x909090;
  }
}

bool
pcdHasField(const std::string& path, const std::string& field)
{
  pcl::PCLPointCloud2 header;
  pcl::PCDReader reader;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0, type = 0;
  unsigned int offset = 0;
  if (reader.readHeader(path, header, origin, orientation, version, type, offset) < 0)
    return false;
  return std::any_of(header.fields.begin(), header.fields.end(),
                     [&field](const pcl::PCLPointField& f) { return f.name == field; });
}

/// What the picture's colours, labels and coordinates mean, for the margin.
struct Meaning
{
  bool class_palette = false;      ///< colours are classColour(label): legend of the classes
  std::string labels = "classes";  ///< a label is one of the "segments", "labels" or "classes"
  std::string unit = "m";          ///< of x and y; empty: geographic (no scale bar)
  std::string crs;                 ///< name of the file's CRS, empty when it declares none
  bool object_classes = false;     ///< classes are pcl_ls3d_segment's object classes
};

bool
loadSamples(const std::string& path, const std::string& by, std::vector<Sample>& out, Meaning& meaning)
{
  // pcl_ls3d's reader first: it refuses empty, truncated and foreign files with one line
  // (PCL's PCD reader crashes on an empty file).
  pcl::PointCloud<pcl_ls3d::PointLiDAR> lidar;
  pcl_ls3d::io::CloudInfo info;
  std::string error;
  if (!pcl_ls3d::io::loadCloud(path, lidar, info, error)) {
    std::fprintf(stderr, "render_top_view: %s\n", error.c_str());
    return false;
  }
  // Metres unless the file's CRS says otherwise (US survey feet in some states); a PCD the
  // tools wrote records its input's CRS in its header.
  const std::string wkt = pcl_ls3d::maps::crsOfFile(info);
  if (!wkt.empty()) {
    meaning.crs = pcl_ls3d::maps::crsName(wkt);
    meaning.unit = pcl_ls3d::maps::crsLinearUnitName(wkt);
  }
  if (by == "class" && info.segments_file) {
    // Its classification field holds the object classes; without one, the labels are ids.
    if (!info.hasField("classification")) {
      std::fprintf(stderr,
                   "render_top_view: %s holds segment ids but no object classes (made with "
                   "-mode mrg or pcl_rg, or by an older pcl_ls3d_segment): use "
                   "-by rgb or -by label\n",
                   path.c_str());
      return false;
    }
    meaning.object_classes = true;
  }
  if (by != "class" && pcl_ls3d::io::fileExtension(path) == "pcd") {
    meaning.labels = info.segments_file ? "segments" : "labels";
    // Its rgba and label fields, which PointLiDAR does not carry; without colours, by label.
    const bool has_rgb = pcdHasField(path, "rgba") || pcdHasField(path, "rgb");
    if (by == "rgb" && !has_rgb)
      std::fprintf(stderr, "render_top_view: %s has no rgb/rgba field: coloured by label\n", path.c_str());
    pcl::PointCloud<pcl::PointXYZRGBL> coloured;
    const auto verbosity = pcl::console::getVerbosityLevel();
    pcl::console::setVerbosityLevel(pcl::console::L_ERROR);  // a missing field is said above
    const bool read = pcl::io::loadPCDFile(path, coloured) >= 0;
    pcl::console::setVerbosityLevel(verbosity);
    if (!read)
      return false;
    for (const auto& p : coloured.points)
      if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
        out.push_back(
            {p.x, p.y, p.z,
             by == "label" || !has_rgb ? pcl_ls3d::evaluation::segmentColour(p.label) : (p.rgba & 0xffffffu),
             p.label});
    return true;
  }
  // LAS, PLY, XYZ: the classification is the label.
  meaning.class_palette = by != "label";
  for (const auto& p : lidar.points)
    out.push_back({p.x, p.y, p.z,
                   by == "label" ? pcl_ls3d::evaluation::segmentColour(p.classification)
                                 : classColour(p.classification),
                   p.classification});
  return true;
}

/// Keeps the points inside the crop box.
void
crop(const std::vector<float>& box, std::vector<Sample>& pts)
{
  if (box.size() != 4)
    return;
  pts.erase(std::remove_if(pts.begin(), pts.end(),
                           [&box](const Sample& p) {
                             return p.x < box[0] || p.x > box[1] || p.y < box[2] || p.y > box[3];
                           }),
            pts.end());
}

/// Turns a side view into the top view the renderer draws: image x to the viewer's right,
/// image y up, and "height" = nearness to the viewer.
bool
toView(const std::string& view, std::vector<Sample>& pts)
{
  for (auto& p : pts) {
    const float x = p.x, y = p.y, z = p.z;
    if (view == "north")
      p = {x, z, -y, p.rgb, p.label};
    else if (view == "east")
      p = {-y, z, -x, p.rgb, p.label};
    else if (view == "south")
      p = {-x, z, y, p.rgb, p.label};
    else if (view == "west")
      p = {y, z, x, p.rgb, p.label};
    else if (view != "top")
      return false;
  }
  return true;
}

struct Options
{
  std::string input, output, by = "rgb", view = "top";
  double pixel = 0.25;
  int splat = 1;
  std::vector<double> crop;  ///< x0, x1, y0, y1, or empty
  bool plain = false;        ///< the picture alone, as before the margin existed
};

constexpr const char* kUsage =
    "Usage: %s INPUT OUT.png|pdf|svg [-pixel m] [-splat n] [-by rgb|label|class]\n"
    "       [-crop x0,x1,y0,y1] [-view top|north|east|south|west] [-plain] [-overwrite]\n"
    "  A map (PNG, PDF or SVG) of the highest point per pixel (side views: the nearest), segment borders "
    "darkened,\n"
    "  in a margin with a scale bar in the cloud's unit (metres unless its CRS says otherwise),\n"
    "  a north arrow (top view) or the side view's direction, a legend of the classes shown\n"
    "  (class colours) and a caption: segments (or classes), points, view and pixel size.\n"
    "  INPUT   SEGMENTS.pcd of pcl_ls3d_segment, or any cloud pcl_ls3d reads (PCD, PLY, LAS, XYZ)\n"
    "  -pixel  pixel size in cloud units (default 0.25)\n"
    "  -splat  each point also paints the pixels within n of its own (default 1: 3 x 3)\n"
    "  -by     rgb: the file's colours (default; LAS, PLY, XYZ: by class); label: a colour per\n"
    "          label (segment, or class); class: ASPRS palette by classification / PCD label\n"
    "  -crop   keep points with x0 <= x <= x1 and y0 <= y <= y1 (the file's local coordinates)\n"
    "  -view   top (default), or a side view looking north, east, south or west\n"
    "  -plain  the picture alone, without the margin (PNG only)\n"
    "  -overwrite  replace an existing output\n";

/// The map's format by the output's extension (png, pdf or svg; checked by parseOptions).
pcl_ls3d::maps::MapFormat
formatOf(const std::string& path)
{
  pcl_ls3d::maps::MapFormat format = pcl_ls3d::maps::MapFormat::PNG;
  pcl_ls3d::maps::parseMapFormat(pcl_ls3d::io::fileExtension(path), format);
  return format;
}

/// The options, checked before the input is read; false with a one-line reason.
bool
parseOptions(int argc, char** argv, Options& o, std::string& why)
{
  namespace tools = pcl_ls3d::tools;
  std::vector<std::string> files;
  if (!tools::splitArguments(argc, argv, 1, {"-pixel", "-splat", "-by", "-crop", "-view"},
                             {"-overwrite", "-plain"}, files, why))
    return false;
  pcl_ls3d::maps::MapFormat format;
  if (files.size() != 2 || !pcl_ls3d::maps::parseMapFormat(pcl_ls3d::io::fileExtension(files[1]), format))
    return (why = "expected INPUT OUT.png, OUT.pdf or OUT.svg (see -h)").empty();
  o.input = files[0];
  o.output = files[1];
  o.plain = pcl::console::find_switch(argc, argv, "-plain");
  if (o.plain && format != pcl_ls3d::maps::MapFormat::PNG)
    return (why = "-plain writes a PNG (the picture's pixels), not " + files[1]).empty();
  long long splat = o.splat;
  if (!tools::numberOption(argc, argv, "-pixel", o.pixel, why) ||
      !tools::integerOption(argc, argv, "-splat", splat, why, 0, 50))
    return false;
  o.splat = static_cast<int>(splat);
  if (!(o.pixel > 0.0))
    return (why = "-pixel must be > 0").empty();
  pcl::console::parse_argument(argc, argv, "-by", o.by);
  if (o.by != "rgb" && o.by != "label" && o.by != "class")
    return (why = "-by takes rgb, label or class, got '" + o.by + "'").empty();
  pcl::console::parse_argument(argc, argv, "-view", o.view);
  if (o.view != "top" && o.view != "north" && o.view != "east" && o.view != "south" && o.view != "west")
    return (why = "-view takes top, north, east, south or west, got '" + o.view + "'").empty();
  std::string crop_text;
  if (pcl::console::parse_argument(argc, argv, "-crop", crop_text) >= 0 &&
      (!tools::parseNumberList(crop_text, o.crop) || o.crop.size() != 4 || !(o.crop[0] < o.crop[1]) ||
       !(o.crop[2] < o.crop[3])))
    return (why = "-crop takes x0,x1,y0,y1 with x0 < x1 and y0 < y1, got '" + crop_text + "'").empty();
  return tools::checkOutputFile(o.output, {o.input}, pcl::console::find_switch(argc, argv, "-overwrite"),
                                why);
}

/// The picture: highest point per pixel over [x0, x0 + w·pixel] × [y0, y0 + h·pixel], borders
/// between labels darkened; `visible` gets the labels that own a pixel.
pcl_ls3d::maps::Image
renderPicture(const std::vector<Sample>& pts, double pixel, int splat, float x0, float y0, int w, int h,
              std::set<std::uint32_t>& visible)
{
  // z-buffer: highest point per pixel; a point's own pixel beats its splats at equal height.
  std::vector<float> top(static_cast<std::size_t>(w) * h, -std::numeric_limits<float>::infinity());
  std::vector<const Sample*> owner(top.size(), nullptr);
  for (const auto& p : pts) {
    const int cx = static_cast<int>((p.x - x0) / pixel), cy = h - 1 - static_cast<int>((p.y - y0) / pixel);
    for (int dy = -splat; dy <= splat; ++dy)
      for (int dx = -splat; dx <= splat; ++dx) {
        const int x = cx + dx, y = cy + dy;
        if (x < 0 || y < 0 || x >= w || y >= h)
          continue;
        const float z = p.z - 0.05f * static_cast<float>(std::abs(dx) + std::abs(dy));
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        if (z > top[i]) {
          top[i] = z;
          owner[i] = &p;
        }
      }
  }
  pcl_ls3d::maps::Image image(w, h);
  std::vector<std::uint8_t>& rgb = image.pixels();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      const Sample* s = owner[i];
      if (!s)
        continue;
      visible.insert(s->label);
      bool border = false;
      for (const auto& [ox, oy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        if (x + ox >= w || y + oy >= h)
          continue;
        const Sample* t = owner[static_cast<std::size_t>(y + oy) * w + x + ox];
        border |= t && t->label != s->label;
      }
      const double f = border ? 0.35 : 1.0;
      rgb[3 * i] = static_cast<unsigned char>(((s->rgb >> 16) & 0xff) * f);
      rgb[3 * i + 1] = static_cast<unsigned char>(((s->rgb >> 8) & 0xff) * f);
      rgb[3 * i + 2] = static_cast<unsigned char>((s->rgb & 0xff) * f);
    }
  return image;
}

// Margin layout, in the spirit of maps::renderRasterMap (same margins, ink and frame).
constexpr int kMargin = 16, kGap = 24, kSwatch = 14, kArrowHeight = 36;
const pcl_ls3d::maps::Rgb kInk{30, 30, 30}, kFrame{90, 90, 90};

/// The side panel's text for a side view: where it looks and what lies left and right.
std::vector<std::string>
viewLines(const std::string& view)
{
  if (view == "north")
    return {"Looking north", "west left, east right"};
  if (view == "east")
    return {"Looking east", "north left, south right"};
  if (view == "south")
    return {"Looking south", "east left, west right"};
  if (view == "west")
    return {"Looking west", "south left, north right"};
  return {};
}

/// \brief The margin's contents: right of the picture a north arrow or the view's direction
///        and the class legend; below it the scale bar, a caption and the CRS.
struct Margin
{
  std::vector<std::string> view_lines;  ///< empty: top view, north arrow
  std::vector<std::uint32_t> classes;   ///< legend rows (class palette only), ascending
  std::string caption, footer, unit;    ///< unit empty: no scale bar (geographic coordinates)
  bool object_classes = false;          ///< legend names: IMRG's object classes, not ASPRS's
};

/// Legend name of a class code: a SEGMENTS.pcd holds IMRG's object classes (64 = car there).
std::string
className(const Margin& m, std::uint32_t code)
{
  pcl_ls3d::segmentation::ObjectClass c;
  if (m.object_classes && code == 0)
    return "no segment";
  if (m.object_classes && pcl_ls3d::segmentation::objectClassFromLasCode(static_cast<int>(code), c))
    return pcl_ls3d::segmentation::toString(c);
  return pcl_ls3d::evaluation::lasClassName(static_cast<int>(code));
}

int
legendRowHeight()
{
  return std::max(kSwatch, pcl_ls3d::maps::Drawing::lineHeight() + 4);
}

int
textWidth(const std::string& text, pcl_ls3d::maps::FontStyle style = pcl_ls3d::maps::FontStyle::REGULAR)
{
  return static_cast<int>(std::ceil(pcl_ls3d::maps::Drawing::textWidth(text, style)));
}

/// Width and height of the side panel.
std::pair<int, int>
panelSize(const Margin& m)
{
  using pcl_ls3d::maps::Drawing;
  using pcl_ls3d::maps::FontStyle;
  int w = 20, h = kArrowHeight;
  if (!m.view_lines.empty()) {
    w = std::max(textWidth(m.view_lines[0], FontStyle::BOLD), textWidth(m.view_lines[1]));
    h = Drawing::lineHeight(FontStyle::BOLD) + Drawing::lineHeight();
  }
  if (!m.classes.empty()) {
    h += 12 + Drawing::lineHeight(FontStyle::BOLD) + static_cast<int>(m.classes.size()) * legendRowHeight();
    const int code_w = textWidth(std::to_string(m.classes.back()));
    for (std::uint32_t c : m.classes)
      w = std::max(w, kSwatch + 12 + code_w + textWidth(className(m, c)));
  }
  return {w, h};
}

void
drawPanel(pcl_ls3d::maps::Drawing& img, int x, int y, const Margin& m)
{
  using Image = pcl_ls3d::maps::Drawing;  // its font metrics
  using pcl_ls3d::maps::FontStyle;
  using pcl_ls3d::maps::TextAlign;
  if (m.view_lines.empty()) {
    pcl_ls3d::maps::drawNorthArrow(img, x + 10, y);
    y += kArrowHeight;
  } else {
    img.text(x, y + Image::ascent(FontStyle::BOLD), m.view_lines[0], kInk, FontStyle::BOLD);
    y += Image::lineHeight(FontStyle::BOLD);
    img.text(x, y + Image::ascent(), m.view_lines[1], kInk);
    y += Image::lineHeight();
  }
  if (m.classes.empty())
    return;
  y += 12;
  img.text(x, y + Image::ascent(FontStyle::BOLD), "Classes", kInk, FontStyle::BOLD);
  y += Image::lineHeight(FontStyle::BOLD);
  const int code_w = textWidth(std::to_string(m.classes.back()));
  for (std::uint32_t c : m.classes) {
    const std::uint32_t rgb = classColour(c);
    // The swatch is the class's own colour, exactly as in the picture (tests find it there).
    const pcl_ls3d::maps::Rgb colour{static_cast<std::uint8_t>(rgb >> 16),
                                     static_cast<std::uint8_t>(rgb >> 8), static_cast<std::uint8_t>(rgb)};
    img.fillRect(x, y + 2, kSwatch, 10, colour);
    img.frame(x - 1, y + 1, kSwatch + 2, 12, kFrame);
    const int base = y + 2 + Image::ascent() - 1;
    img.text(x + kSwatch + 6 + code_w, base, std::to_string(c), kInk, FontStyle::REGULAR, TextAlign::RIGHT);
    img.text(x + kSwatch + 12 + code_w, base, className(m, c), kInk);
    y += legendRowHeight();
  }
}

/// The picture at (kMargin, kMargin), framed, with the margin around it; `bar` and `bar_y` say
/// what scale bar was drawn where (printed, so that scripts and tests can find it).
pcl_ls3d::maps::Drawing
decorate(const pcl_ls3d::maps::Image& picture, double pixel, const Margin& m, pcl_ls3d::maps::ScaleBar& bar,
         int& bar_y)
{
  using Image = pcl_ls3d::maps::Drawing;  // its font metrics
  const int w = picture.width(), h = picture.height();
  const auto [panel_w, panel_h] = panelSize(m);
  const int line = Image::lineHeight();
  int width = kMargin + w + kGap + panel_w + kMargin;
  width = std::max(width, 2 * kMargin + std::max(textWidth(m.caption), textWidth(m.footer)));
  const int below = kMargin + std::max(h, panel_h) + 12;  // top of the scale bar
  const int height = below + (m.unit.empty() ? 0 : 30) + line + (m.footer.empty() ? 0 : line) + kMargin;
  pcl_ls3d::maps::Drawing img(width, height);
  img.setTitle(m.caption);
  img.image(picture, kMargin, kMargin);
  img.frame(kMargin - 1, kMargin - 1, w + 2, h + 2, kFrame);
  drawPanel(img, kMargin + w + kGap, kMargin, m);
  int y = bar_y = below;
  if (!m.unit.empty()) {
    // At least a 160-pixel reference: under a small picture, "0" and the label would overlap.
    bar = pcl_ls3d::maps::drawScaleBar(img, kMargin, y, std::max(w, 160), pixel, m.unit);
    y += 30;
  }
  img.text(kMargin, y + Image::ascent(), m.caption, kInk);
  y += line;
  if (!m.footer.empty())
    img.text(kMargin, y + Image::ascent(), m.footer, kFrame);
  return img;
}

/// "12 segments, 9600 points, top view, pixel 0.25 m" (segments: label 0 is no segment).
std::string
caption(const std::vector<Sample>& pts, const Meaning& meaning, const std::string& view, double pixel)
{
  std::set<std::uint32_t> labels;
  for (const auto& p : pts)
    if (p.label != 0 || meaning.labels != "segments")
      labels.insert(p.label);
  char text[256];
  const std::string where = view == "top" ? "top view" : "side view looking " + view;
  // "1 segment", "1 class", "1 label": the names are plurals ending in s.
  const std::string name =
      labels.size() == 1
          ? meaning.labels.substr(0, meaning.labels.size() - (meaning.labels == "classes" ? 2 : 1))
          : meaning.labels;
  std::snprintf(text, sizeof(text), "%zu %s, %zu points, %s, pixel %g%s%s", labels.size(), name.c_str(),
                pts.size(), where.c_str(), pixel, meaning.unit.empty() ? "" : " ", meaning.unit.c_str());
  return text;
}

}  // namespace

int
main(int argc, char** argv)
{
  if (pcl::console::find_switch(argc, argv, "-h") || pcl::console::find_switch(argc, argv, "--help")) {
    std::printf(kUsage, argv[0]);
    return 0;
  }
  Options o;
  std::string why;
  if (!parseOptions(argc, argv, o, why)) {
    std::fprintf(stderr, "render_top_view: %s\n", why.c_str());
    return 1;
  }
  const double pixel = o.pixel;
  std::vector<Sample> pts;
  Meaning meaning;
  if (!loadSamples(o.input, o.by, pts, meaning))
    return 1;
  const std::vector<float> box(o.crop.begin(), o.crop.end());
  crop(box, pts);
  toView(o.view, pts);
  if (pts.empty()) {
    std::fprintf(stderr, "render_top_view: no finite point of '%s'%s\n", o.input.c_str(),
                 o.crop.empty() ? "" : " inside -crop");
    return 1;
  }
  float x0 = pts[0].x, x1 = x0, y0 = pts[0].y, y1 = y0;
  for (const auto& p : pts) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  const int w = static_cast<int>((x1 - x0) / pixel) + 1, h = static_cast<int>((y1 - y0) / pixel) + 1;
  if (static_cast<double>(w) * h > 64e6) {
    std::fprintf(stderr, "render_top_view: image %d x %d too large, raise -pixel\n", w, h);
    return 1;
  }
  std::set<std::uint32_t> visible;
  const pcl_ls3d::maps::Image picture = renderPicture(pts, pixel, o.splat, x0, y0, w, h, visible);
  Margin m;
  m.view_lines = viewLines(o.view);
  if (meaning.class_palette)  // the classes that own a pixel: a hidden one would only confuse
    m.classes.assign(visible.begin(), visible.end());
  m.object_classes = meaning.object_classes;
  m.caption = caption(pts, meaning, o.view, pixel);
  m.footer = meaning.crs.empty() ? "No CRS in the file: lengths in metres assumed" : meaning.crs;
  m.unit = meaning.unit;
  pcl_ls3d::maps::ScaleBar bar;
  int bar_y = 0;
  std::string error;
  const pcl_ls3d::maps::Drawing map =
      o.plain ? pcl_ls3d::maps::Drawing() : decorate(picture, pixel, m, bar, bar_y);
  const bool written = o.plain ? pcl_ls3d::maps::writePng(o.output, picture, error)
                               : map.write(o.output, formatOf(o.output), error, true);
  if (!written) {
    std::fprintf(stderr, "render_top_view: %s\n", error.c_str());
    return 1;
  }
  if (o.plain) {
    std::printf("Wrote %s (%d x %d pixels of %.3g, %zu points, x %.1f..%.1f, y %.1f..%.1f)\n",
                o.output.c_str(), w, h, pixel, pts.size(), x0, x1, y0, y1);
    return 0;
  }
  std::printf("Wrote %s (%d x %d pixels; picture %d x %d pixels of %.3g at %d,%d, %zu points, "
              "x %.1f..%.1f, y %.1f..%.1f)\n",
              o.output.c_str(), map.width(), map.height(), w, h, pixel, kMargin, kMargin, pts.size(), x0, x1,
              y0, y1);
  std::printf("Caption: %s\n", m.caption.c_str());
  if (bar.pixels > 0)
    std::printf("Scale bar %g %s = %d px at %d,%d\n", bar.length, m.unit.c_str(), bar.pixels, kMargin, bar_y);
  else
    std::printf("No scale bar: %s\n",
                m.unit.empty() ? "geographic coordinates" : "the picture is too narrow");
  return 0;
}
