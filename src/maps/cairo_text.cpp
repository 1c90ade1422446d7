#include "cairo_text.h"

namespace pcl_ls3d {
namespace maps {
namespace detail {

namespace {

// Length of the valid UTF-8 character at text[i] (1–4), 0 when it is not one (stray
// continuation byte, truncated or overlong sequence, surrogate, beyond U+10FFFF).
std::size_t
characterLength(const std::string& text, std::size_t i)
{
  const unsigned char c = static_cast<unsigned char>(text[i]);
  const std::size_t n = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
  if (n <= 1 || i + n > text.size())
    return n == 1 ? 1 : 0;
  unsigned cp = c & (0x7Fu >> n);
  for (std::size_t k = 1; k < n; ++k) {
    const unsigned char b = static_cast<unsigned char>(text[i + k]);
    if ((b >> 6) != 2)
      return 0;
    cp = (cp << 6) | (b & 0x3Fu);
  }
  const unsigned smallest[5] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < smallest[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
    return 0;
  return n;
}

}  // namespace

void
selectFont(cairo_t* cr, FontStyle style)
{
  const bool bold = style == FontStyle::BOLD;
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, bold ? 14.0 : 12.0);
  // Unhinted metrics: a text is as wide in a PNG as in a PDF, so one layout serves all.
  cairo_font_options_t* options = cairo_font_options_create();
  cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);
  cairo_font_options_set_hint_style(options, CAIRO_HINT_STYLE_SLIGHT);
  cairo_font_options_set_antialias(options, CAIRO_ANTIALIAS_GRAY);
  cairo_set_font_options(cr, options);
  cairo_font_options_destroy(options);
}

std::string
validUtf8(const std::string& text)
{
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = characterLength(text, i);
    if (n == 0 || text[i] == '\0') {
      out += '?';
      ++i;
      continue;
    }
    out.append(text, i, n);
    i += n;
  }
  return out;
}

}  // namespace detail
}  // namespace maps
}  // namespace pcl_ls3d
