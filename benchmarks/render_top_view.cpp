/// \file render_top_view.cpp
/// \brief Top-view PNG of a segmented or classified cloud, to look at a segmentation as a user
///        would: each pixel shows the highest point's colour, and pixels whose neighbour shows
///        another segment are darkened so segment borders (and fragmentation) are visible.
///
/// Usage: render_top_view INPUT OUT.png [-pixel m] [-splat n] [-by rgb|label|class]
///                       [-crop x0,x1,y0,y1] [-view top|north|east|south|west] [-overwrite]
///   INPUT  SEGMENTS.pcd of pcl_ls3d_segment (x y z rgba label), or any cloud pcl_ls3d reads
///          (-by class colours by the LAS classification / PCD label with a fixed palette)
///   -pixel pixel size in cloud units (default 0.25)
///   -splat each point also paints the pixels within n of its own (default 1: 3 × 3)
///   -by    rgb: the file's colours (default; a PCD without rgb/rgba: by label); label: a colour
///          per label (LAS, PLY, XYZ: per class); class: ASPRS palette (ground brown,
///          vegetation greens, building red, wire yellow)
///   -crop  keep only points with x0 ≤ x ≤ x1 and y0 ≤ y ≤ y1 (the file's local coordinates)
///   -view  top (default); or a side view looking north, east, south or west, the nearest
///          point per pixel shown (facades, storeys, what hangs under a roof)
/// Not run by CTest: a viewing aid for docs/BENCHMARKS.md.

#include "../tools/tool_arguments.h"

#include <pcl_ls3d/evaluation/segmentation_labels.h>
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/maps/png_io.h>

#include <pcl/console/parse.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
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
    case 2: return 0xa0785a;
    case 3: return 0x9ad07a;
    case 4: return 0x4caf50;
    case 5: return 0x1b5e20;
    case 6: return 0xd03030;
    case 14: return 0xffe000;
    case 15: return 0xff8c00;
    case 9: return 0x3070ff;
    default: return c >= 64 ? 0x2040c0 : 0x909090;
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

bool
loadSamples(const std::string& path, const std::string& by, std::vector<Sample>& out)
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
  if (by != "class" && pcl_ls3d::io::fileExtension(path) == "pcd") {
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
        out.push_back({p.x, p.y, p.z,
                       by == "label" || !has_rgb ? pcl_ls3d::evaluation::segmentColour(p.label)
                                                 : (p.rgba & 0xffffffu),
                       p.label});
    return true;
  }
  // LAS, PLY, XYZ: the classification is the label.
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
  pts.erase(std::remove_if(pts.begin(), pts.end(), [&box](const Sample& p) {
              return p.x < box[0] || p.x > box[1] || p.y < box[2] || p.y > box[3];
            }), pts.end());
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
};

constexpr const char* kUsage =
    "Usage: %s INPUT OUT.png [-pixel m] [-splat n] [-by rgb|label|class] [-crop x0,x1,y0,y1]\n"
    "       [-view top|north|east|south|west] [-overwrite]\n";

/// The options, checked before the input is read; false with a one-line reason.
bool
parseOptions(int argc, char** argv, Options& o, std::string& why)
{
  namespace tools = pcl_ls3d::tools;
  std::vector<std::string> files;
  if (!tools::splitArguments(argc, argv, 1, {"-pixel", "-splat", "-by", "-crop", "-view"}, {"-overwrite"},
                             files, why))
    return false;
  if (files.size() != 2 || pcl_ls3d::io::fileExtension(files[1]) != "png")
    return (why = "expected INPUT OUT.png (see -h)").empty();
  o.input = files[0];
  o.output = files[1];
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
  return tools::checkOutputFile(o.output, {o.input}, pcl::console::find_switch(argc, argv, "-overwrite"), why);
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
  const int splat = o.splat;
  const std::string& output = o.output;
  std::vector<Sample> pts;
  if (!loadSamples(o.input, o.by, pts))
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
  std::string error;
  if (!pcl_ls3d::maps::writePng(output, image, error)) {
    std::fprintf(stderr, "render_top_view: %s\n", error.c_str());
    return 1;
  }
  std::printf("Wrote %s (%d x %d pixels of %.3g, %zu points, x %.1f..%.1f, y %.1f..%.1f)\n",
              output.c_str(), w, h, pixel, pts.size(), x0, x1, y0, y1);
  return 0;
}
