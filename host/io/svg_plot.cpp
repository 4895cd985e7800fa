// svg_plot.cpp — layout: a fixed 800x500 canvas, the plot frame on the left, the legend in a column
// on its right. All coordinates are formatted with std::to_chars, independent of the C locale.
#include "io/svg_plot.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "io/atomic_file.h"

namespace seasim {

namespace {

constexpr double kWidth = 800, kHeight = 500;
constexpr double kLeft = 80, kTop = 45, kBottom = 60, kGap = 20;
// Okabe & Ito's colour-blind-safe palette (yellow left out: too faint on white), then black/grey.
constexpr const char* kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                    "#E69F00", "#56B4E9", "#000000", "#999999"};
constexpr int kNumColours = sizeof kColours / sizeof kColours[0];
constexpr int kNumMarkers = 4;  // circle, square, triangle, diamond

std::string num(double v) {  // SVG coordinate: two decimals are sub-pixel
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, std::round(v * 100.0) / 100.0);
  return std::string(buf, res.ptr);
}

std::string escapeXml(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // Control characters other than tab/newline are not allowed in XML 1.0.
        if (static_cast<unsigned char>(ch) >= 0x20 || ch == '\t' || ch == '\n') out += ch;
    }
  }
  return out;
}

// One axis: the data range in plot units (log10 of the value on a log axis) and its ticks.
struct Axis {
  bool log = false;
  double lo = 0, hi = 1;              // plot-unit range drawn
  std::vector<double> major, minor;   // plot units
  std::vector<std::string> labels;    // one per major tick; may contain <tspan> markup
};

bool usable(double v, bool log) { return std::isfinite(v) && (!log || v > 0.0); }
double toPlot(double v, bool log) { return log ? std::log10(v) : v; }

std::string fixed(double v, int decimals) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  return std::string(buf, res.ptr);
}

// Tick label for a value that is a multiple of `step`.
std::string linearLabel(double v, double step, double max_abs) {
  if (std::fabs(v) < step * 1e-6) v = 0.0;
  const int step_exp = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  if (max_abs >= 1e5 || (max_abs > 0 && max_abs < 1e-3)) {
    if (v == 0.0) return "0";
    const int e = static_cast<int>(std::floor(std::log10(std::fabs(v)) + 1e-9));
    const int digits = std::clamp(e - step_exp, 0, 6);
    std::string mant = fixed(v / std::pow(10.0, e), digits);
    return mant + "e" + std::to_string(e);
  }
  return fixed(v, std::max(0, -step_exp));
}

Axis linearAxis(double lo, double hi) {
  Axis a;
  if (!(hi > lo)) {  // one value (or none): widen around it
    const double pad = lo == 0.0 ? 1.0 : std::fabs(lo) * 0.1;
    lo -= pad;
    hi += pad;
  }
  // 1-2-5 step giving about 5 intervals; the range is extended to whole steps.
  const double raw = (hi - lo) / 5.0;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  const double step = (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * mag;
  a.lo = std::floor(lo / step + 1e-9) * step;
  a.hi = std::ceil(hi / step - 1e-9) * step;
  const double max_abs = std::max(std::fabs(a.lo), std::fabs(a.hi));
  const int n = static_cast<int>(std::lround((a.hi - a.lo) / step));
  for (int i = 0; i <= n; ++i) {
    const double v = a.lo + i * step;
    a.major.push_back(v);
    a.labels.push_back(linearLabel(v, step, max_abs));
  }
  return a;
}

Axis logAxis(double lo, double hi) {  // lo, hi in log10 units
  Axis a;
  a.log = true;
  a.lo = std::floor(lo + 1e-9);
  a.hi = std::ceil(hi - 1e-9);
  if (a.hi <= a.lo) a.hi = a.lo + 1;
  const int decades = static_cast<int>(a.hi - a.lo);
  const int every = std::max(1, (decades + 9) / 10);  // at most ~10 labelled decades
  const bool plain = a.lo >= -3 && a.hi <= 4;         // 0.001 ... 10000 read better as numbers
  for (int k = static_cast<int>(a.lo); k <= static_cast<int>(a.hi); ++k) {
    if ((k - static_cast<int>(a.lo)) % every != 0) {
      a.minor.push_back(k);
      continue;
    }
    a.major.push_back(k);
    if (plain) a.labels.push_back(k >= 0 ? fixed(std::pow(10.0, k), 0) : fixed(std::pow(10.0, k), -k));
    else a.labels.push_back("10<tspan dy=\"-7\" font-size=\"10\">" + std::to_string(k) + "</tspan>");
  }
  if (decades <= 6)
    for (int k = static_cast<int>(a.lo); k < static_cast<int>(a.hi); ++k)
      for (int m = 2; m <= 9; ++m) a.minor.push_back(k + std::log10(static_cast<double>(m)));
  return a;
}

Axis makeAxis(bool log, bool any, double lo, double hi) {
  if (!any) return log ? logAxis(0, 1) : linearAxis(0, 1);
  return log ? logAxis(lo, hi) : linearAxis(lo, hi);
}

std::string marker(int shape, double x, double y, const char* colour) {
  const std::string fill = "fill=\"" + std::string(colour) + "\"";
  switch (shape) {
    case 0: return "<circle cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"3.5\" " + fill + "/>";
    case 1:
      return "<rect x=\"" + num(x - 3.2) + "\" y=\"" + num(y - 3.2) + "\" width=\"6.4\" height=\"6.4\" " + fill + "/>";
    case 2:
      return "<path d=\"M" + num(x) + " " + num(y - 4.2) + "L" + num(x + 4) + " " + num(y + 3) + "L" +
             num(x - 4) + " " + num(y + 3) + "Z\" " + fill + "/>";
    default:
      return "<path d=\"M" + num(x) + " " + num(y - 4.5) + "L" + num(x + 4) + " " + num(y) + "L" + num(x) +
             " " + num(y + 4.5) + "L" + num(x - 4) + " " + num(y) + "Z\" " + fill + "/>";
  }
}

}  // namespace

std::string renderSvgPlot(const PlotSpec& spec) {
  // Data ranges over the usable points only.
  bool any = false;
  double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
  for (const PlotSeries& s : spec.series) {
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (!usable(s.x[i], spec.log_x) || !usable(s.y[i], spec.log_y)) continue;
      const double px = toPlot(s.x[i], spec.log_x), py = toPlot(s.y[i], spec.log_y);
      any = true;
      xlo = std::min(xlo, px);
      xhi = std::max(xhi, px);
      ylo = std::min(ylo, py);
      yhi = std::max(yhi, py);
    }
  }
  const Axis ax = makeAxis(spec.log_x, any, xlo, xhi);
  const Axis ay = makeAxis(spec.log_y, any, ylo, yhi);

  // Legend column width from the longest name (about 7 px per character at 12 px).
  std::size_t longest = 0;
  for (const PlotSeries& s : spec.series) longest = std::max(longest, s.name.size());
  const double legend_w = spec.series.empty() ? 0.0 : std::min(260.0, 40.0 + 7.0 * static_cast<double>(longest));
  const double x0 = kLeft, x1 = kWidth - kGap - legend_w - (legend_w > 0 ? kGap : 0);
  const double y0 = kHeight - kBottom, y1 = kTop;  // y0 = bottom edge of the frame
  auto sx = [&](double p) { return x0 + (p - ax.lo) / (ax.hi - ax.lo) * (x1 - x0); };
  auto sy = [&](double p) { return y0 - (p - ay.lo) / (ay.hi - ay.lo) * (y0 - y1); };

  std::string svg;
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(kWidth) + "\" height=\"" + num(kHeight) +
         "\" viewBox=\"0 0 " + num(kWidth) + " " + num(kHeight) + "\" font-family=\"sans-serif\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  if (!spec.title.empty())
    svg += "<text x=\"" + num((x0 + x1) / 2) + "\" y=\"26\" text-anchor=\"middle\" font-size=\"16\" font-weight=\"bold\">" +
           escapeXml(spec.title) + "</text>\n";

  // Grid and ticks.
  svg += "<g stroke=\"#e3e3e3\" stroke-width=\"1\">\n";
  for (double t : ax.major) svg += "<line x1=\"" + num(sx(t)) + "\" y1=\"" + num(y0) + "\" x2=\"" + num(sx(t)) + "\" y2=\"" + num(y1) + "\"/>\n";
  for (double t : ay.major) svg += "<line x1=\"" + num(x0) + "\" y1=\"" + num(sy(t)) + "\" x2=\"" + num(x1) + "\" y2=\"" + num(sy(t)) + "\"/>\n";
  svg += "</g>\n<g stroke=\"#333\" stroke-width=\"1\">\n";
  for (double t : ax.major) svg += "<line x1=\"" + num(sx(t)) + "\" y1=\"" + num(y0) + "\" x2=\"" + num(sx(t)) + "\" y2=\"" + num(y0 + 6) + "\"/>\n";
  for (double t : ax.minor) svg += "<line x1=\"" + num(sx(t)) + "\" y1=\"" + num(y0) + "\" x2=\"" + num(sx(t)) + "\" y2=\"" + num(y0 + 3) + "\"/>\n";
  for (double t : ay.major) svg += "<line x1=\"" + num(x0 - 6) + "\" y1=\"" + num(sy(t)) + "\" x2=\"" + num(x0) + "\" y2=\"" + num(sy(t)) + "\"/>\n";
  for (double t : ay.minor) svg += "<line x1=\"" + num(x0 - 3) + "\" y1=\"" + num(sy(t)) + "\" x2=\"" + num(x0) + "\" y2=\"" + num(sy(t)) + "\"/>\n";
  svg += "</g>\n";
  svg += "<rect x=\"" + num(x0) + "\" y=\"" + num(y1) + "\" width=\"" + num(x1 - x0) + "\" height=\"" + num(y0 - y1) +
         "\" fill=\"none\" stroke=\"#333\" stroke-width=\"1.2\"/>\n";

  // Tick labels (labels are generated here, so their markup needs no escaping).
  svg += "<g font-size=\"12\" fill=\"#222\">\n";
  for (std::size_t i = 0; i < ax.major.size(); ++i)
    svg += "<text class=\"xtick\" x=\"" + num(sx(ax.major[i])) + "\" y=\"" + num(y0 + 20) + "\" text-anchor=\"middle\">" +
           ax.labels[i] + "</text>\n";
  for (std::size_t i = 0; i < ay.major.size(); ++i)
    svg += "<text class=\"ytick\" x=\"" + num(x0 - 9) + "\" y=\"" + num(sy(ay.major[i]) + 4) + "\" text-anchor=\"end\">" +
           ay.labels[i] + "</text>\n";
  svg += "</g>\n";
  if (!spec.x_label.empty())
    svg += "<text x=\"" + num((x0 + x1) / 2) + "\" y=\"" + num(kHeight - 16) + "\" text-anchor=\"middle\" font-size=\"13\">" +
           escapeXml(spec.x_label) + "</text>\n";
  if (!spec.y_label.empty())
    svg += "<text transform=\"translate(20 " + num((y0 + y1) / 2) + ") rotate(-90)\" text-anchor=\"middle\" font-size=\"13\">" +
           escapeXml(spec.y_label) + "</text>\n";
  if (!any)
    svg += "<text x=\"" + num((x0 + x1) / 2) + "\" y=\"" + num((y0 + y1) / 2) +
           "\" text-anchor=\"middle\" font-size=\"14\" fill=\"#888\">no data</text>\n";

  // Series: polylines broken at skipped points, then markers on top.
  for (std::size_t k = 0; k < spec.series.size(); ++k) {
    const PlotSeries& s = spec.series[k];
    const char* colour = kColours[k % kNumColours];
    const int shape = static_cast<int>(k % kNumMarkers);
    svg += "<g class=\"series\" stroke=\"" + std::string(colour) + "\">\n";
    std::string points, markers;
    int in_run = 0;
    auto flush = [&]() {
      if (in_run >= 2) svg += "<polyline fill=\"none\" stroke-width=\"1.8\" points=\"" + points + "\"/>\n";
      points.clear();
      in_run = 0;
    };
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (!usable(s.x[i], spec.log_x) || !usable(s.y[i], spec.log_y)) {
        flush();
        continue;
      }
      const double px = sx(toPlot(s.x[i], spec.log_x)), py = sy(toPlot(s.y[i], spec.log_y));
      points += (in_run ? " " : "") + num(px) + "," + num(py);
      ++in_run;
      markers += marker(shape, px, py, colour) + "\n";
    }
    flush();
    svg += "</g>\n<g stroke=\"none\">\n" + markers + "</g>\n";
  }

  // Legend.
  if (!spec.series.empty()) {
    const double lx = x1 + kGap;
    svg += "<g font-size=\"12\" fill=\"#222\">\n";
    for (std::size_t k = 0; k < spec.series.size(); ++k) {
      const double ly = y1 + 10 + 20.0 * static_cast<double>(k);
      const char* colour = kColours[k % kNumColours];
      svg += "<line x1=\"" + num(lx) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(lx + 24) + "\" y2=\"" + num(ly) +
             "\" stroke=\"" + colour + "\" stroke-width=\"1.8\"/>\n";
      svg += marker(static_cast<int>(k % kNumMarkers), lx + 12, ly, colour) + "\n";
      svg += "<text x=\"" + num(lx + 30) + "\" y=\"" + num(ly + 4) + "\">" + escapeXml(spec.series[k].name) + "</text>\n";
    }
    svg += "</g>\n";
  }
  svg += "</svg>\n";
  return svg;
}

void writeSvgPlot(const std::string& path, const PlotSpec& spec) { writeTextAtomic(path, renderSvgPlot(spec)); }

}  // namespace seasim
