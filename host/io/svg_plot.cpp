// svg_plot.cpp — layout: a fixed 800x500 canvas; the title on top, the legend in a column on the
// right, the frame in what is left after the margins that the measured tick labels, axis labels and
// legend need (io/svg_text.h). All coordinates are formatted with std::to_chars, independent of the
// C locale.
#include "io/svg_plot.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "io/atomic_file.h"
#include "io/svg_text.h"

namespace seasim {

namespace {

constexpr double kWidth = 800, kHeight = 500;
constexpr double kPad = 10, kGap = 20;  // canvas edge to any text; frame to legend
constexpr double kTitleSize = 16, kMinTitleSize = 12, kLabelSize = 13, kTickSize = 12, kLegendSize = 12;
constexpr double kPointLabelSize = 10;
constexpr double kLineHeight = 1.25;   // baseline to baseline, in font sizes
constexpr double kAscent = 0.93, kDescent = 0.24;  // DejaVu Sans, in font sizes
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

Axis categoryAxis(const std::vector<std::string>& names) {  // ticks at 0 .. n-1, half a step of room each side
  Axis a;
  a.lo = -0.5;
  a.hi = static_cast<double>(names.size()) - 0.5;
  for (size_t i = 0; i < names.size(); ++i) {
    a.major.push_back(static_cast<double>(i));
    a.labels.push_back(escapeXml(names[i]));
  }
  if (names.empty()) a.hi = 0.5;
  return a;
}

Axis makeAxis(bool log, bool any, double lo, double hi) {
  if (!any) return log ? logAxis(0, 1) : linearAxis(0, 1);
  return log ? logAxis(lo, hi) : linearAxis(lo, hi);
}

struct LabelBox {
  double x0, y0, x1, y1;
  bool overlaps(const LabelBox& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

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

// One <text> with every attribute a reader needs to find its box.
std::string text(double x, double y, double size, const char* anchor, const std::string& body,
                 const std::string& extra = "") {
  return "<text" + extra + " x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + num(size) +
         "\" text-anchor=\"" + anchor + "\">" + body + "</text>\n";
}

// Tick label sizes: a log axis's "10^k" is "10" at 12 px and k at 10 px, 7 px up.
double tickWidth(const std::string& label) {
  const size_t sup = label.find("<tspan");
  if (sup == std::string::npos) return svgTextWidth(svgPlainText(label), kTickSize);
  return svgTextWidth(svgPlainText(label.substr(0, sup)), kTickSize) + svgTextWidth(svgPlainText(label.substr(sup)), 10);
}

// Where everything goes: the axes, the text lines, and the frame [x0, x1] x [y1, y0] (y0 at the bottom).
struct Layout {
  bool categorical = false, log_x = false, any = false;
  Axis ax, ay;
  double title_size = kTitleSize;
  std::vector<std::string> title_lines, ylabel_lines, xlabel_lines;
  std::vector<std::vector<std::string>> legend_lines, xtick_lines;
  double legend_w = 0, xtick_size = kTickSize, xtick_h = 0;
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  double sx(double p) const { return x0 + (p - ax.lo) / (ax.hi - ax.lo) * (x1 - x0); }
  double sy(double p) const { return y0 - (p - ay.lo) / (ay.hi - ay.lo) * (y0 - y1); }
};

// The axes over the data ranges of the usable points only.
void layoutAxes(const PlotSpec& spec, Layout& L) {
  L.categorical = !spec.x_categories.empty();
  L.log_x = spec.log_x && !L.categorical;
  double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
  for (const PlotSeries& s : spec.series) {
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (!usable(s.x[i], L.log_x) || !usable(s.y[i], spec.log_y)) continue;
      const double px = toPlot(s.x[i], L.log_x), py = toPlot(s.y[i], spec.log_y);
      L.any = true;
      xlo = std::min(xlo, px);
      xhi = std::max(xhi, px);
      ylo = std::min(ylo, py);
      yhi = std::max(yhi, py);
    }
  }
  L.ax = L.categorical ? categoryAxis(spec.x_categories) : makeAxis(L.log_x, L.any, xlo, xhi);
  L.ay = makeAxis(spec.log_y, L.any, ylo, yhi);
}

// The title (shrunk to fit one line down to kMinTitleSize, then wrapped) and the legend (names wrapped
// to at most a third of the canvas; the column as wide as its widest line).
void layoutTitleAndLegend(const PlotSpec& spec, Layout& L) {
  const double text_w = kWidth - 2 * kPad;
  while (L.title_size > kMinTitleSize && svgTextWidth(spec.title, L.title_size, true) > text_w) L.title_size -= 1;
  L.title_lines = spec.title.empty() ? std::vector<std::string>{} : wrapSvgText(spec.title, L.title_size, text_w, true);
  const double legend_text_max = kWidth / 3 - 30;
  double legend_text_w = 0;
  for (const PlotSeries& s : spec.series) {
    L.legend_lines.push_back(wrapSvgText(s.name, kLegendSize, legend_text_max));
    for (const auto& l : L.legend_lines.back()) legend_text_w = std::max(legend_text_w, svgTextWidth(l, kLegendSize));
  }
  L.legend_w = spec.series.empty() ? 0.0 : 30 + legend_text_w;
}

// X tick labels: numbers on one line; categories wrapped to their share of the frame, at 12 px or
// smaller until each fits in three lines.
void layoutXTicks(Layout& L) {
  const double slot =
      L.categorical ? (L.x1 - L.x0) / std::max<double>(1.0, static_cast<double>(L.ax.major.size())) - 4 : 1e9;
  for (;;) {
    L.xtick_lines.clear();
    size_t most = 1;
    for (const auto& l : L.ax.labels) {
      L.xtick_lines.push_back(L.categorical ? wrapSvgText(svgPlainText(l), L.xtick_size, slot)
                                            : std::vector<std::string>{l});
      most = std::max(most, L.xtick_lines.back().size());
    }
    if (most <= 3 || L.xtick_size <= 8) break;
    L.xtick_size -= 1;
  }
}

Layout layoutPlot(const PlotSpec& spec) {
  Layout L;
  layoutAxes(spec, L);
  layoutTitleAndLegend(spec, L);
  const double title_h = static_cast<double>(L.title_lines.size()) * L.title_size * kLineHeight;
  double ytick_w = 0;
  for (const auto& l : L.ay.labels) ytick_w = std::max(ytick_w, tickWidth(l));
  // Frame left/right: the y label (rotated, its lines side by side), the tick labels, the legend.
  const double y_label_room = 300;  // the frame's least height: the y label wraps to it
  L.ylabel_lines = spec.y_label.empty() ? std::vector<std::string>{} : wrapSvgText(spec.y_label, kLabelSize, y_label_room);
  const double ylabel_w = static_cast<double>(L.ylabel_lines.size()) * kLabelSize * kLineHeight;
  L.x0 = kPad + ylabel_w + (L.ylabel_lines.empty() ? 0 : 6) + ytick_w + 9;
  L.x1 = kWidth - kPad - L.legend_w - (L.legend_w > 0 ? kGap : 0);
  // The first and last x tick labels are centred on the frame's edges: room for their halves.
  if (!L.ax.labels.empty() && !L.categorical) {
    L.x0 = std::max(L.x0, kPad + tickWidth(L.ax.labels.front()) / 2);
    L.x1 = std::min(L.x1, kWidth - kPad - (L.legend_w > 0 ? L.legend_w + kGap : 0) - tickWidth(L.ax.labels.back()) / 2);
  }
  layoutXTicks(L);
  size_t xtick_rows = 1;
  for (const auto& l : L.xtick_lines) xtick_rows = std::max(xtick_rows, l.size());
  L.xlabel_lines = spec.x_label.empty() ? std::vector<std::string>{} : wrapSvgText(spec.x_label, kLabelSize, L.x1 - L.x0);
  // Frame top/bottom: the title above; ticks, tick labels and the x label below.
  L.y1 = kPad + title_h + 12;
  L.xtick_h = 6 + 4 + static_cast<double>(xtick_rows) * L.xtick_size * kLineHeight;
  const double xlabel_h = static_cast<double>(L.xlabel_lines.size()) * kLabelSize * kLineHeight;
  L.y0 = kHeight - kPad - xlabel_h - (L.xlabel_lines.empty() ? 0 : 4) - L.xtick_h;
  return L;
}

// Grid lines, ticks and the frame.
std::string svgFrame(const Layout& L) {
  auto line = [](double xa, double ya, double xb, double yb) {
    return "<line x1=\"" + num(xa) + "\" y1=\"" + num(ya) + "\" x2=\"" + num(xb) + "\" y2=\"" + num(yb) + "\"/>\n";
  };
  std::string svg = "<g stroke=\"#e3e3e3\" stroke-width=\"1\">\n";
  for (double t : L.ax.major) svg += line(L.sx(t), L.y0, L.sx(t), L.y1);
  for (double t : L.ay.major) svg += line(L.x0, L.sy(t), L.x1, L.sy(t));
  svg += "</g>\n<g stroke=\"#333\" stroke-width=\"1\">\n";
  for (double t : L.ax.major) svg += line(L.sx(t), L.y0, L.sx(t), L.y0 + 6);
  for (double t : L.ax.minor) svg += line(L.sx(t), L.y0, L.sx(t), L.y0 + 3);
  for (double t : L.ay.major) svg += line(L.x0 - 6, L.sy(t), L.x0, L.sy(t));
  for (double t : L.ay.minor) svg += line(L.x0 - 3, L.sy(t), L.x0, L.sy(t));
  svg += "</g>\n";
  svg += "<rect x=\"" + num(L.x0) + "\" y=\"" + num(L.y1) + "\" width=\"" + num(L.x1 - L.x0) + "\" height=\"" +
         num(L.y0 - L.y1) + "\" fill=\"none\" stroke=\"#333\" stroke-width=\"1.2\"/>\n";
  return svg;
}

// Tick labels (numeric labels are generated here, so their markup needs no escaping) and axis labels.
std::string svgLabels(const Layout& L) {
  std::string svg = "<g fill=\"#222\">\n";
  for (std::size_t i = 0; i < L.ax.major.size(); ++i) {
    if (L.categorical) {
      for (size_t r = 0; r < L.xtick_lines[i].size(); ++r)
        svg += text(L.sx(L.ax.major[i]), L.y0 + 10 + L.xtick_size * (kAscent + kLineHeight * static_cast<double>(r)),
                    L.xtick_size, "middle", escapeXml(L.xtick_lines[i][r]), " class=\"xtick\"");
    } else {
      svg += text(L.sx(L.ax.major[i]), L.y0 + 10 + kTickSize * kAscent, kTickSize, "middle", L.ax.labels[i],
                  " class=\"xtick\"");
    }
  }
  for (std::size_t i = 0; i < L.ay.major.size(); ++i)
    svg += text(L.x0 - 9, L.sy(L.ay.major[i]) + 4, kTickSize, "end", L.ay.labels[i], " class=\"ytick\"");
  svg += "</g>\n";
  for (size_t i = 0; i < L.xlabel_lines.size(); ++i)
    svg += text((L.x0 + L.x1) / 2, L.y0 + L.xtick_h + 4 + kLabelSize * (kAscent + kLineHeight * static_cast<double>(i)),
                kLabelSize, "middle", escapeXml(L.xlabel_lines[i]), " class=\"xlabel\"");
  // The y label turned a quarter left: its baseline runs up at x = the line's right edge.
  for (size_t i = 0; i < L.ylabel_lines.size(); ++i) {
    const double bx = kPad + kLabelSize * (kAscent + kLineHeight * static_cast<double>(i));
    svg += "<text class=\"ylabel\" x=\"0\" y=\"0\" font-size=\"" + num(kLabelSize) +
           "\" text-anchor=\"middle\" transform=\"translate(" + num(bx) + " " + num((L.y0 + L.y1) / 2) +
           ") rotate(-90)\">" + escapeXml(L.ylabel_lines[i]) + "</text>\n";
  }
  if (!L.any) svg += text((L.x0 + L.x1) / 2, (L.y0 + L.y1) / 2, 14, "middle", "no data", " fill=\"#888\"");
  return svg;
}

// A point's label: above right of the point, else below right, above left, below left, then the same a
// line and two lines further out: the first place inside the frame that no earlier label (placed)
// covers (else the first inside the frame).
std::string pointLabel(const Layout& L, double px, double py, const std::string& label, const char* colour,
                       std::vector<LabelBox>& placed) {
  const double w = svgTextWidth(label, kPointLabelSize);
  const double step = kPointLabelSize * kLineHeight;
  struct Place {
    bool left;
    double baseline;
  };
  std::vector<Place> places;
  for (int k = 0; k < 3; ++k)
    for (bool left : {false, true}) {
      places.push_back({left, py - 6 - k * step});
      places.push_back({left, py + 6 + kPointLabelSize * kAscent + k * step});
    }
  auto boxOf = [&](bool left, double baseline) {
    const double bx0 = left ? px - 6 - w : px + 6;
    return LabelBox{bx0, baseline - kPointLabelSize * kAscent, bx0 + w, baseline + kPointLabelSize * kDescent};
  };
  int chosen = -1;
  for (int pass = 0; pass < 2 && chosen < 0; ++pass)
    for (int c = 0; c < static_cast<int>(places.size()) && chosen < 0; ++c) {
      const LabelBox b = boxOf(places[c].left, places[c].baseline);
      const bool inside = b.x0 >= L.x0 && b.x1 <= L.x1 && b.y0 >= L.y1 && b.y1 <= L.y0;
      const bool free = std::none_of(placed.begin(), placed.end(), [&](const LabelBox& o) { return o.overlaps(b); });
      if (inside && (free || pass == 1)) chosen = c;
    }
  if (chosen < 0) chosen = px + 6 + w > L.x1 ? 2 : 0;  // wider than the frame allows: at least on the canvas side
  placed.push_back(boxOf(places[chosen].left, places[chosen].baseline));
  return text(places[chosen].left ? px - 6 : px + 6, places[chosen].baseline, kPointLabelSize,
              places[chosen].left ? "end" : "start", escapeXml(label),
              " class=\"point\" fill=\"" + std::string(colour) + "\"");
}

// Series k: its polylines broken at skipped points, then markers on top, then point labels.
std::string svgSeries(const Layout& L, const PlotSpec& spec, std::size_t k, std::vector<LabelBox>& placed) {
  const PlotSeries& s = spec.series[k];
  const char* colour = kColours[k % kNumColours];
  const int shape = static_cast<int>(k % kNumMarkers);
  std::string svg = "<g class=\"series\" stroke=\"" + std::string(colour) + "\">\n";
  std::string points, markers, labels;
  int in_run = 0;
  auto flush = [&]() {
    if (in_run >= 2 && !L.categorical) svg += "<polyline fill=\"none\" stroke-width=\"1.8\" points=\"" + points + "\"/>\n";
    points.clear();
    in_run = 0;
  };
  const std::size_t n = std::min(s.x.size(), s.y.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (!usable(s.x[i], L.log_x) || !usable(s.y[i], spec.log_y)) {
      flush();
      continue;
    }
    const double px = L.sx(toPlot(s.x[i], L.log_x)), py = L.sy(toPlot(s.y[i], spec.log_y));
    points += (in_run ? " " : "") + num(px) + "," + num(py);
    ++in_run;
    markers += marker(shape, px, py, colour) + "\n";
    if (i < s.labels.size() && !s.labels[i].empty()) labels += pointLabel(L, px, py, s.labels[i], colour, placed);
  }
  flush();
  return svg + "</g>\n<g stroke=\"none\">\n" + markers + "</g>\n" + labels;
}

// Legend: one entry per series, its name's lines under each other.
std::string svgLegend(const Layout& L, const PlotSpec& spec) {
  if (spec.series.empty()) return "";
  const double lx = L.x1 + kGap;
  double ly = L.y1 + 10;
  std::string svg = "<g fill=\"#222\">\n";
  for (std::size_t k = 0; k < spec.series.size(); ++k) {
    const char* colour = kColours[k % kNumColours];
    svg += "<line x1=\"" + num(lx) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(lx + 24) + "\" y2=\"" + num(ly) +
           "\" stroke=\"" + colour + "\" stroke-width=\"1.8\"/>\n";
    svg += marker(static_cast<int>(k % kNumMarkers), lx + 12, ly, colour) + "\n";
    for (size_t r = 0; r < L.legend_lines[k].size(); ++r)
      svg += text(lx + 30, ly + 4 + kLegendSize * kLineHeight * static_cast<double>(r), kLegendSize, "start",
                  escapeXml(L.legend_lines[k][r]), " class=\"legend\"");
    ly += 8 + kLegendSize * kLineHeight * static_cast<double>(L.legend_lines[k].size());
  }
  return svg + "</g>\n";
}

}  // namespace

std::string renderSvgPlot(const PlotSpec& spec) {
  const Layout L = layoutPlot(spec);
  std::string svg;
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(kWidth) + "\" height=\"" + num(kHeight) +
         "\" viewBox=\"0 0 " + num(kWidth) + " " + num(kHeight) + "\" font-family=\"sans-serif\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for (size_t i = 0; i < L.title_lines.size(); ++i)
    svg += text(kWidth / 2, kPad + L.title_size * (kAscent + kLineHeight * static_cast<double>(i)), L.title_size,
                "middle", escapeXml(L.title_lines[i]), " class=\"title\" font-weight=\"bold\"");
  svg += svgFrame(L);
  svg += svgLabels(L);
  std::vector<LabelBox> placed;
  for (std::size_t k = 0; k < spec.series.size(); ++k) svg += svgSeries(L, spec, k, placed);
  svg += svgLegend(L, spec);
  svg += "</svg>\n";
  return svg;
}

void writeSvgPlot(const std::string& path, const PlotSpec& spec) { writeTextAtomic(path, renderSvgPlot(spec)); }

}  // namespace seasim
