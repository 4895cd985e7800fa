// svg_plot.h — a self-contained SVG line plot (no external library) for the sweep outputs: error
// against time, convergence, throughput against wavelength count. Lines with markers, one colour
// and marker shape per series (colour-blind-safe Okabe–Ito palette), axes with "nice" ticks (1-2-5
// steps, or every decade with minor ticks at 2..9 on log axes), grid, title, axis labels, legend.
// Points with a NaN/Inf coordinate, or a non-positive one on a log axis, are skipped and break the
// line there. Empty series and an empty plot render without error (an empty frame).
#pragma once
#include <string>
#include <vector>

namespace seasim {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;  // same length; extra values in the longer one are ignored
};

struct PlotSpec {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  std::vector<PlotSeries> series;
};

// The complete SVG document (starts with an XML declaration).
std::string renderSvgPlot(const PlotSpec& spec);

// renderSvgPlot written atomically to `path` (parent folders created).
void writeSvgPlot(const std::string& path, const PlotSpec& spec);

}  // namespace seasim
