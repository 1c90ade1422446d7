#pragma once
/// \file drawing.h
/// \brief A picture recorded as vector graphics by cairo: rectangles, lines, polygons, colour
///        gradients, embedded pixel images and antialiased text (DejaVu Sans through
///        fontconfig), written as PNG, PDF or SVG from the one recording.
///
/// Coordinates are pixels of the PNG: (0, 0) is the top left corner and pixel (i, j) covers
/// [i, i + 1) × [j, j + 1), so a rectangle or a one-pixel line on whole coordinates covers whole
/// pixels in one colour. A PDF page has the size of the PNG shown at 96 dpi (one pixel is 0.75
/// pt); an SVG is sized in pixels. Text stays text in a PDF (selectable, searchable); cairo draws
/// the glyphs of an SVG as outlines, so it looks the same where DejaVu is not installed.

#include <pcl_ls3d/maps/colour_map.h>
#include <pcl_ls3d/maps/image.h>
#include <pcl_ls3d/maps/map_format.h>

#include <Eigen/Core>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace pcl_ls3d {
namespace maps {

enum class FontStyle
{
  REGULAR,
  BOLD
};
enum class TextAlign
{
  LEFT,
  CENTRE,
  RIGHT
};

/// \brief A recorded picture of a fixed size. Move-only: it owns cairo's recording.
class Drawing
{
public:
  /// An empty drawing (nothing could be drawn); empty() is true.
  Drawing();
  /// A drawing of width × height pixels filled with \a background.
  Drawing(int width, int height, Rgb background = {255, 255, 255});
  ~Drawing();
  Drawing(Drawing&& other) noexcept;
  Drawing&
  operator=(Drawing&& other) noexcept;
  Drawing(const Drawing&) = delete;
  Drawing&
  operator=(const Drawing&) = delete;

  int
  width() const
  {
    return width_;
  }
  int
  height() const
  {
    return height_;
  }
  bool
  empty() const
  {
    return width_ <= 0 || height_ <= 0;
  }
  /// The document title a PDF carries in its metadata.
  void
  setTitle(const std::string& title)
  {
    title_ = title;
  }

  /// Fills [x, x + w) × [y, y + h) with \a c at \a opacity ∈ [0, 1].
  void
  fillRect(double x, double y, double w, double h, Rgb c, double opacity = 1.0);
  /// A frame of \a line_width inside [x, x + w) × [y, y + h) (one pixel: the rectangle's
  /// outermost pixels).
  void
  frame(double x, double y, double w, double h, Rgb c, double line_width = 1.0);
  /// A straight line of \a line_width with flat ends; \a dash > 0 draws it in dashes and gaps
  /// of that length.
  void
  line(double x0, double y0, double x1, double y1, Rgb c, double line_width = 1.0, double dash = 0.0);
  /// Lines of one colour and width in one path, each element (x0, y0, x1, y1); \a square_ends
  /// extend each by half the width (pixel-centred lines then cover their end pixels), else
  /// the ends are flat.
  void
  lines(const std::vector<Eigen::Vector4d>& segments, Rgb c, double line_width, bool square_ends = true);
  /// Fills the polygon through \a corners.
  void
  fillPolygon(const std::vector<Eigen::Vector2d>& corners, Rgb c);
  /// Fills [x, x + w) × [y, y + h) with a vertical gradient: (offset, colour) pairs, offset 0 at
  /// the top and 1 at the bottom, non-decreasing; two stops at one offset make a sharp step.
  void
  verticalGradient(double x, double y, double w, double h, const std::vector<std::pair<double, Rgb>>& stops);
  /// Draws \a pixels with its top left corner at (x, y), each pixel a square of \a scale
  /// (unsmoothed in PNG and PDF; SVG viewers smooth an enlarged image, so where sharp cells
  /// matter enlarge the pixels first and draw at scale 1).
  void
  image(const Image& pixels, double x, double y, double scale = 1.0);
  /// Draws UTF-8 text with its baseline at y (invalid bytes shown as '?'); returns its width.
  double
  text(double x, double y, const std::string& utf8, Rgb c, FontStyle style = FontStyle::REGULAR,
       TextAlign align = TextAlign::LEFT);

  /// Advance width of a text (the same in every format).
  static double
  textWidth(const std::string& utf8, FontStyle style = FontStyle::REGULAR);
  /// Line height and ascent of a font, rounded up to whole pixels.
  static int
  lineHeight(FontStyle style = FontStyle::REGULAR);
  static int
  ascent(FontStyle style = FontStyle::REGULAR);

  /// The drawing as the pixels of its PNG.
  Image
  rasterise() const;
  /// Writes the drawing to \a path; refuses to replace an existing file unless \a overwrite, and
  /// leaves no partial file. False with a one-line reason.
  bool
  write(const std::string& path, MapFormat format, std::string& error, bool overwrite = false) const;

private:
  /// \brief cairo's recording surface and context (src/maps/drawing_recording.h).
  struct Recording;

  int width_ = 0, height_ = 0;
  std::string title_;
  std::unique_ptr<Recording> recording_;
};

}  // namespace maps
}  // namespace pcl_ls3d
