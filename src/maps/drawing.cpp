// What a Drawing records: the primitives maps are made of, on cairo's recording surface.
#include "cairo_image.h"
#include "cairo_text.h"
#include "drawing_recording.h"

#include <algorithm>
#include <cmath>

namespace pcl_ls3d {
namespace maps {

namespace {

void
setColour(cairo_t* cr, Rgb c, double opacity = 1.0)
{
  cairo_set_source_rgba(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0, std::clamp(opacity, 0.0, 1.0));
}

bool
finite(std::initializer_list<double> values)
{
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

// A scratch context for measuring text outside any drawing (layouts measure before drawing).
struct Measure
{
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
  cairo_t* cr = cairo_create(surface);

  explicit Measure(FontStyle style)
  {
    detail::selectFont(cr, style);
  }
  ~Measure()
  {
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
  }
};

}  // namespace

Drawing::Drawing() = default;
Drawing::~Drawing() = default;
Drawing::Drawing(Drawing&& other) noexcept = default;
Drawing&
Drawing::operator=(Drawing&& other) noexcept = default;

Drawing::Drawing(int width, int height, Rgb background)
    : width_(std::max(0, width)), height_(std::max(0, height))
{
  if (empty())
    return;
  recording_ = std::make_unique<Recording>(width_, height_);
  fillRect(0, 0, width_, height_, background);
}

void
Drawing::fillRect(double x, double y, double w, double h, Rgb c, double opacity)
{
  if (!recording_ || !finite({x, y, w, h, opacity}) || w <= 0.0 || h <= 0.0)
    return;
  cairo_t* cr = recording_->cr;
  setColour(cr, c, opacity);
  cairo_rectangle(cr, x, y, w, h);
  cairo_fill(cr);
}

void
Drawing::frame(double x, double y, double w, double h, Rgb c, double line_width)
{
  if (!recording_ || !finite({x, y, w, h, line_width}) || w <= 0.0 || h <= 0.0 || line_width <= 0.0)
    return;
  cairo_t* cr = recording_->cr;
  const double half = std::min({line_width, w, h}) / 2.0;
  setColour(cr, c);
  cairo_set_line_width(cr, 2.0 * half);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_MITER);
  cairo_rectangle(cr, x + half, y + half, w - 2.0 * half, h - 2.0 * half);
  cairo_stroke(cr);
}

void
Drawing::line(double x0, double y0, double x1, double y1, Rgb c, double line_width, double dash)
{
  if (!recording_ || !finite({x0, y0, x1, y1, line_width, dash}) || line_width <= 0.0)
    return;
  cairo_t* cr = recording_->cr;
  cairo_save(cr);
  setColour(cr, c);
  cairo_set_line_width(cr, line_width);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  if (dash > 0.0)
    cairo_set_dash(cr, &dash, 1, 0.0);
  cairo_move_to(cr, x0, y0);
  cairo_line_to(cr, x1, y1);
  cairo_stroke(cr);
  cairo_restore(cr);
}

void
Drawing::lines(const std::vector<Eigen::Vector4d>& segments, Rgb c, double line_width, bool square_ends)
{
  if (!recording_ || segments.empty() || !std::isfinite(line_width) || line_width <= 0.0)
    return;
  cairo_t* cr = recording_->cr;
  cairo_save(cr);
  setColour(cr, c);
  cairo_set_line_width(cr, line_width);
  cairo_set_line_cap(cr, square_ends ? CAIRO_LINE_CAP_SQUARE : CAIRO_LINE_CAP_BUTT);
  for (const Eigen::Vector4d& s : segments)
    if (s.allFinite()) {
      cairo_move_to(cr, s[0], s[1]);
      cairo_line_to(cr, s[2], s[3]);
    }
  cairo_stroke(cr);
  cairo_restore(cr);
}

void
Drawing::fillPolygon(const std::vector<Eigen::Vector2d>& corners, Rgb c)
{
  if (!recording_ || corners.size() < 3)
    return;
  cairo_t* cr = recording_->cr;
  for (const Eigen::Vector2d& p : corners)
    if (p.allFinite())
      cairo_line_to(cr, p.x(), p.y());
  cairo_close_path(cr);
  setColour(cr, c);
  cairo_fill(cr);
}

void
Drawing::verticalGradient(double x, double y, double w, double h,
                          const std::vector<std::pair<double, Rgb>>& stops)
{
  if (!recording_ || stops.empty() || !finite({x, y, w, h}) || w <= 0.0 || h <= 0.0)
    return;
  cairo_t* cr = recording_->cr;
  cairo_pattern_t* gradient = cairo_pattern_create_linear(0.0, y, 0.0, y + h);
  for (const auto& [offset, c] : stops)
    cairo_pattern_add_color_stop_rgb(gradient, std::clamp(offset, 0.0, 1.0), c.r / 255.0, c.g / 255.0,
                                     c.b / 255.0);
  cairo_set_source(cr, gradient);
  cairo_rectangle(cr, x, y, w, h);
  cairo_fill(cr);
  cairo_pattern_destroy(gradient);
}

void
Drawing::image(const Image& pixels, double x, double y, double scale)
{
  if (!recording_ || pixels.empty() || !finite({x, y, scale}) || scale <= 0.0)
    return;
  cairo_surface_t* surface = detail::surfaceOf(pixels);
  cairo_t* cr = recording_->cr;
  if (cairo_surface_status(surface) == CAIRO_STATUS_SUCCESS) {
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, scale, scale);
    cairo_set_source_surface(cr, surface, 0.0, 0.0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_rectangle(cr, 0.0, 0.0, pixels.width(), pixels.height());
    cairo_fill(cr);
    cairo_restore(cr);
  }
  cairo_surface_destroy(surface);  // the recording holds its own reference
}

double
Drawing::text(double x, double y, const std::string& utf8, Rgb c, FontStyle style, TextAlign align)
{
  const std::string s = detail::validUtf8(utf8);
  const double w = textWidth(s, style);
  if (!recording_ || s.empty() || !finite({x, y}))
    return w;
  cairo_t* cr = recording_->cr;
  cairo_save(cr);
  detail::selectFont(cr, style);
  const double left = align == TextAlign::LEFT ? x : align == TextAlign::CENTRE ? x - w / 2.0 : x - w;
  cairo_move_to(cr, left, y);
  setColour(cr, c);
  cairo_show_text(cr, s.c_str());
  cairo_new_path(cr);
  cairo_restore(cr);
  return w;
}

double
Drawing::textWidth(const std::string& utf8, FontStyle style)
{
  const Measure m(style);
  cairo_text_extents_t e;
  cairo_text_extents(m.cr, detail::validUtf8(utf8).c_str(), &e);
  return e.x_advance;
}

int
Drawing::lineHeight(FontStyle style)
{
  const Measure m(style);
  cairo_font_extents_t e;
  cairo_font_extents(m.cr, &e);
  return static_cast<int>(std::ceil(e.height));
}

int
Drawing::ascent(FontStyle style)
{
  const Measure m(style);
  cairo_font_extents_t e;
  cairo_font_extents(m.cr, &e);
  return static_cast<int>(std::ceil(e.ascent));
}

}  // namespace maps
}  // namespace pcl_ls3d
