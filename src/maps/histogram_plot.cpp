// Overlaid histograms in percent per bin, with axes, reference lines and a legend.
#include <pcl_ls3d/maps/map_rendering.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pcl_ls3d {
namespace maps {

namespace {

const Rgb kInk{30, 30, 30}, kGrid{225, 225, 225}, kMark{120, 120, 120};

// The x range: the style's, or the 0.5–99.5 % range of all values (symmetric about 0 when the
// values straddle it, so before and after read on one centred axis).
void
xRange(const std::vector<HistogramSeries>& series, const HistogramStyle& style, double& lo, double& hi)
{
  lo = style.min;
  hi = style.max;
  if (std::isfinite(lo) && std::isfinite(hi) && hi > lo)
    return;
  std::vector<double> all;
  for (const auto& s : series)
    for (double v : s.values)
      if (std::isfinite(v))
        all.push_back(v);
  if (all.empty()) {
    lo = -1.0;
    hi = 1.0;
    return;
  }
  std::sort(all.begin(), all.end());
  const auto at = [&](double q) { return all[static_cast<std::size_t>(q * (all.size() - 1))]; };
  lo = at(0.005);
  hi = at(0.995);
  if (lo < 0.0 && hi > 0.0)
    lo = -(hi = std::max(-lo, hi));
  if (!(hi > lo)) {
    lo -= 0.5;
    hi += 0.5;
  }
}

std::vector<double>
percentPerBin(const std::vector<double>& values, double lo, double hi, int bins, std::size_t& outside)
{
  std::vector<double> h(static_cast<std::size_t>(bins), 0.0);
  std::size_t n = 0;
  outside = 0;
  for (double v : values) {
    if (!std::isfinite(v))
      continue;
    ++n;
    const double f = (v - lo) / (hi - lo) * bins;
    if (f < 0.0 || f >= bins)
      ++outside;
    else
      h[static_cast<std::size_t>(f)] += 1.0;
  }
  for (double& x : h)
    x = n ? 100.0 * x / static_cast<double>(n) : 0.0;
  return h;
}

std::string
label(double v, double step)
{
  char buf[32];
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  std::string s = buf;
  if (s == "-0" || s.find_first_not_of("-0.") == std::string::npos)
    s = "0";
  if (!s.empty() && s[0] == '-')
    s = "\u2212" + s.substr(1);
  return s;
}

}  // namespace

Image
renderHistogram(const std::vector<HistogramSeries>& series, const HistogramStyle& style)
{
  const int left = 64, right = 24, top = 40 + static_cast<int>(series.size()) * 4, bottom = 56;
  Image img(std::max(300, style.width), std::max(200, style.height));
  const int pw = img.width() - left - right, ph = img.height() - top - bottom;
  const int bins = std::max(1, style.bins);
  double lo = 0.0, hi = 1.0;
  xRange(series, style, lo, hi);
  std::vector<std::vector<double>> h;
  std::vector<std::size_t> outside;
  double ymax = 0.0;
  for (const auto& s : series) {
    outside.emplace_back();
    h.push_back(percentPerBin(s.values, lo, hi, bins, outside.back()));
    ymax = std::max(ymax, *std::max_element(h.back().begin(), h.back().end()));
  }
  const double ystep = niceStep(std::max(ymax, 1e-9) * 1.1, 5);
  ymax = std::ceil(std::max(ymax, 1e-9) * 1.1 / ystep) * ystep;
  auto X = [&](double v) { return left + static_cast<int>(std::lround((v - lo) / (hi - lo) * pw)); };
  auto Y = [&](double p) { return top + ph - static_cast<int>(std::lround(p / ymax * ph)); };

  // Grid and axes.
  for (double p = 0.0; p <= ymax + 1e-9; p += ystep) {
    img.drawLine(left, Y(p), left + pw, Y(p), kGrid);
    img.drawText(left - 6, Y(p) + 4, label(p, ystep) + " %", kInk, FontStyle::REGULAR, TextAlign::RIGHT);
  }
  const double xstep = niceStep(hi - lo, 8);
  for (double v = std::ceil(lo / xstep) * xstep; v <= hi + 1e-9 * xstep; v += xstep) {
    img.drawLine(X(v), top + ph, X(v), top + ph + 4, kInk);
    img.drawText(X(v), top + ph + 18, label(v, xstep), kInk, FontStyle::REGULAR, TextAlign::CENTRE);
  }
  for (double m : style.marks)
    if (m > lo && m < hi)
      for (int y = top; y < top + ph; y += 6)
        img.drawLine(X(m), y, X(m), std::min(y + 2, top + ph), kMark);

  // Bars: translucent fill, then the outline of each series.
  for (std::size_t s = 0; s < series.size(); ++s)
    for (int b = 0; b < bins; ++b) {
      const int x0 = X(lo + (hi - lo) * b / bins), x1 = X(lo + (hi - lo) * (b + 1) / bins);
      for (int y = Y(h[s][static_cast<std::size_t>(b)]); y < top + ph; ++y)
        for (int x = x0; x < x1; ++x)
          img.blend(x, y, series[s].colour, 0.35);
    }
  for (std::size_t s = 0; s < series.size(); ++s) {
    int prev = top + ph;
    for (int b = 0; b < bins; ++b) {
      const int x0 = X(lo + (hi - lo) * b / bins), x1 = X(lo + (hi - lo) * (b + 1) / bins);
      const int y = Y(h[s][static_cast<std::size_t>(b)]);
      img.drawLine(x0, prev, x0, y, series[s].colour);
      img.drawLine(x0, y, x1, y, series[s].colour);
      prev = y;
    }
    img.drawLine(left + pw, prev, left + pw, top + ph, series[s].colour);
  }
  img.drawLine(left, top, left, top + ph, kInk);
  img.drawLine(left, top + ph, left + pw, top + ph, kInk);

  // Title, axis label, legend (with the share outside the range).
  img.drawText(left, 20, style.title, kInk, FontStyle::BOLD);
  img.drawText(left + pw / 2, img.height() - 14, style.x_label, kInk, FontStyle::REGULAR, TextAlign::CENTRE);
  int ly = top + 8;
  for (std::size_t s = 0; s < series.size(); ++s) {
    std::string text = series[s].label;
    if (outside[s] > 0) {
      char buf[64];
      std::snprintf(buf, sizeof(buf), " (%zu outside the axis)", outside[s]);
      text += buf;
    }
    const int w = Image::textWidth(text);
    const int x = left + pw - w - 8;
    img.fillRect(x - 22, ly - 9, 14, 10, series[s].colour);
    img.drawText(x, ly, text, kInk);
    ly += Image::lineHeight() + 2;
  }
  return img;
}

}  // namespace maps
}  // namespace pcl_ls3d
