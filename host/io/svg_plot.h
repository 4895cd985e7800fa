// svg_plot.h — a self-contained SVG line plot (no external library) for the sweep outputs: error
// against time, convergence, throughput against wavelength count. Lines with markers, one colour
// and marker shape per series (colour-blind-safe Okabe–Ito palette), axes with "nice" ticks (1-2-5
// steps, or every decade with minor ticks at 2..9 on log axes), grid, title, axis labels, legend.
// Points with a NaN/Inf coordinate, or a non-positive one on a log axis, are skipped and break the
// line there. Empty series and an empty plot render without error (an empty frame).
//
// Text is laid out so that none leaves the 800 x 500 canvas (widths by io/svg_text.h, an upper
// bound for the sans-serif faces browsers pick): a long title shrinks, then wraps; legend names,
// axis labels and category labels wrap; the margins grow to hold the tick labels, the axis labels
// and the legend. Every <text> carries its own x, y, font-size and text-anchor, so a reader (the
// plot-layout test) can find its box.
#pragma once
#include <string>
#include <vector>

namespace seasim {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;  // same length; extra values in the longer one are ignored
  std::vector<std::string> labels{};  // optional, one per point: drawn beside it (a sweep's knob values)
};

struct PlotSpec {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  std::vector<PlotSeries> series;
  // Not empty: the x axis is categorical; x values are indices 0, 1, ... into these names, one tick
  // per category, labelled with its name (wrapped to the category's width); log_x is ignored, and
  // points are not joined by lines (nothing lies between two categories).
  std::vector<std::string> x_categories{};
};

// The complete SVG document (starts with an XML declaration).
std::string renderSvgPlot(const PlotSpec& spec);

// renderSvgPlot written atomically to `path` (parent folders created).
void writeSvgPlot(const std::string& path, const PlotSpec& spec);

}  // namespace seasim
