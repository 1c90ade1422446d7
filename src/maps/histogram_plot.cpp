// Overlaid histograms in percent per bin, with axes, reference lines and a legend.
#include <pcl_ls3d/maps/map_rendering.h>

#include "colour_bar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pcl_ls3d {
namespace maps {

namespace {

using detail::kInk;
const Rgb kGrid{225, 225, 225}, kMark{120, 120, 120};

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

// The plot area and its value → pixel mapping.
struct Plot
{
  int left = 64, top = 0, width = 0, height = 0;
  double lo = 0.0, hi = 1.0, ymax = 1.0, ystep = 1.0;

  int
  x(double v) const
  {
    return left + static_cast<int>(std::lround((v - lo) / (hi - lo) * width));
  }
  int
  y(double percent) const
  {
    return top + height - static_cast<int>(std::lround(percent / ymax * height));
  }
  int
  bottom() const
  {
    return top + height;
  }
};

// Horizontal grid with percent labels, x ticks with labels, dashed reference marks.
void
drawAxes(Drawing& d, const Plot& p, const HistogramStyle& style)
{
  for (double v = 0.0; v <= p.ymax + 1e-9; v += p.ystep) {
    d.fillRect(p.left, p.y(v), p.width + 1, 1, kGrid);
    d.text(p.left - 6, p.y(v) + 4, label(v, p.ystep) + " %", kInk, FontStyle::REGULAR, TextAlign::RIGHT);
  }
  const double xstep = niceStep(p.hi - p.lo, 8);
  for (double v = std::ceil(p.lo / xstep) * xstep; v <= p.hi + 1e-9 * xstep; v += xstep) {
    d.fillRect(p.x(v), p.bottom(), 1, 5, kInk);
    d.text(p.x(v) + 0.5, p.bottom() + 18, label(v, xstep), kInk, FontStyle::REGULAR, TextAlign::CENTRE);
  }
  for (double m : style.marks)
    if (m > p.lo && m < p.hi)
      d.line(p.x(m) + 0.5, p.top, p.x(m) + 0.5, p.bottom(), kMark, 1.0, 3.0);
}

// Each series: a translucent fill under its bars, then its outline as a step line.
void
drawBars(Drawing& d, const Plot& p, const std::vector<HistogramSeries>& series,
         const std::vector<std::vector<double>>& h, int bins)
{
  auto edge = [&](int b) { return p.x(p.lo + (p.hi - p.lo) * b / bins); };
  for (std::size_t s = 0; s < series.size(); ++s)
    for (int b = 0; b < bins; ++b) {
      const int y = p.y(h[s][static_cast<std::size_t>(b)]);
      d.fillRect(edge(b), y, edge(b + 1) - edge(b), p.bottom() - y, series[s].colour, 0.35);
    }
  for (std::size_t s = 0; s < series.size(); ++s) {
    // Pixel-centred lines (+0.5) with square ends cover the same pixels as a one-pixel step.
    std::vector<Eigen::Vector4d> outline;
    int prev = p.bottom();
    for (int b = 0; b < bins; ++b) {
      const int y = p.y(h[s][static_cast<std::size_t>(b)]);
      outline.emplace_back(edge(b) + 0.5, prev + 0.5, edge(b) + 0.5, y + 0.5);
      outline.emplace_back(edge(b) + 0.5, y + 0.5, edge(b + 1) + 0.5, y + 0.5);
      prev = y;
    }
    outline.emplace_back(p.left + p.width + 0.5, prev + 0.5, p.left + p.width + 0.5, p.bottom() + 0.5);
    d.lines(outline, series[s].colour, 1.0);
  }
  d.fillRect(p.left, p.top, 1, p.height + 1, kInk);
  d.fillRect(p.left, p.bottom(), p.width + 1, 1, kInk);
}

// Legend at the top right, on a light backing so that bars and marks under it do not cross its
// text: a swatch and the label per series, with the count outside the axis.
void
drawLegend(Drawing& d, const Plot& p, const std::vector<HistogramSeries>& series,
           const std::vector<std::size_t>& outside)
{
  std::vector<std::string> texts;
  double widest = 0.0;
  for (std::size_t s = 0; s < series.size(); ++s) {
    texts.push_back(series[s].label);
    if (outside[s] > 0)
      texts.back() += " (" + std::to_string(outside[s]) + " outside the axis)";
    widest = std::max(widest, Drawing::textWidth(texts.back()));
  }
  const int row = Drawing::lineHeight() + 2;
  const double right = p.left + p.width - 4;
  d.fillRect(right - widest - 30, p.top + 2, widest + 30, row * static_cast<double>(texts.size()) + 2,
             {255, 255, 255}, 0.85);
  int ly = p.top + 8;
  for (std::size_t s = 0; s < texts.size(); ++s) {
    const double x = p.left + p.width - Drawing::textWidth(texts[s]) - 8;
    d.fillRect(std::floor(x) - 22, ly - 9, 14, 10, series[s].colour);
    d.text(x, ly, texts[s], kInk);
    ly += row;
  }
}

}  // namespace

Drawing
renderHistogram(const std::vector<HistogramSeries>& series, const HistogramStyle& style)
{
  Drawing d(std::max(300, style.width), std::max(200, style.height));
  Plot p;
  p.top = 40 + static_cast<int>(series.size()) * 4;
  p.width = d.width() - p.left - 24;
  p.height = d.height() - p.top - 56;
  const int bins = std::max(1, style.bins);
  xRange(series, style, p.lo, p.hi);
  std::vector<std::vector<double>> h;
  std::vector<std::size_t> outside;
  double ymax = 0.0;
  for (const auto& s : series) {
    outside.emplace_back();
    h.push_back(percentPerBin(s.values, p.lo, p.hi, bins, outside.back()));
    ymax = std::max(ymax, *std::max_element(h.back().begin(), h.back().end()));
  }
  p.ystep = niceStep(std::max(ymax, 1e-9) * 1.1, 5);
  p.ymax = std::ceil(std::max(ymax, 1e-9) * 1.1 / p.ystep) * p.ystep;
  d.setTitle(style.title);
  drawAxes(d, p, style);
  drawBars(d, p, series, h, bins);
  d.text(p.left, 20, style.title, kInk, FontStyle::BOLD);
  d.text(p.left + p.width / 2.0, d.height() - 14, style.x_label, kInk, FontStyle::REGULAR, TextAlign::CENTRE);
  drawLegend(d, p, series, outside);
  return d;
}

}  // namespace maps
}  // namespace pcl_ls3d
