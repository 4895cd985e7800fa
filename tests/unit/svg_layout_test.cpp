// svg_layout_test.cpp — io/svg_plot.h lays text out inside its canvas: every text box of the plots
// the commands write (their titles, labels and legends, with the longest device and scene names met
// on our machines and longer) lies inside the canvas; sweep points carry their knob values; a
// categorical axis has one tick per category, labelled with its name. io/svg_text.h's measure is
// DejaVu Sans's advances.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "io/svg_plot.h"
#include "io/svg_text.h"
#include "svg_layout_check.h"

namespace seasim {
namespace {

// The longest OpenCL device name met so far (PoCL on the CI machine), and a longer one.
const std::string kPocl = "pthread-skylake-avx512-AMD EPYC 7B13 64-Core Processor";
const std::string kLong = "NVIDIA GeForce RTX 4090 Laptop GPU with a vendor string as long as they come (OpenCL 3.0 CUDA)";

PlotSeries line(const std::string& name, int n, double scale) {
  PlotSeries s{name, {}, {}};
  for (int i = 0; i < n; ++i) {
    s.x.push_back(3.0 * (1 << i));
    s.y.push_back(scale * (1 + i * i));
  }
  return s;
}

// The specs `bench`, `sweep`, `ocean --bench`, `ocean` (caustic PDF), `seashore-study` and
// `underwater-study` build (host/cli/*), with long names filled in.
std::vector<PlotSpec> commandPlots(const std::string& device) {
  std::vector<PlotSpec> plots;
  PlotSpec bench;
  bench.title = "Kernel time vs wavelength count (" + device + ")";
  bench.x_label = "wavelength bands";
  bench.y_label = "ms per frame";
  bench.log_x = true;
  bench.series = {line("all passes (OpenCL)", 5, 10), line("raycast + kd_multiple (OpenCL)", 5, 8),
                  line("same on C++/oneTBB", 5, 30), line("same on C++/oneTBB, vectorised", 5, 12)};
  plots.push_back(bench);
  PlotSpec lights;
  lights.title = "Shafts time vs light count: spot_sphere_with_five_lamps_and_a_long_name (" + device + ")";
  lights.x_label = "spotlights";
  lights.y_label = "ms per frame";
  lights.series = {line("shadow maps + shafts", 5, 3), line("shafts kernel", 5, 2)};
  plots.push_back(lights);
  PlotSpec sweep;
  sweep.title = "Error vs time: underwater_regions_open_water_with_objects";
  sweep.x_label = "kernel time (ms)";
  sweep.y_label = "RMSE (8-bit levels)";
  sweep.log_y = true;
  PlotSeries err{"rmse (8-bit levels)", {0.5, 1.0, 2.0, 40.0}, {20.0, 4.0, 1.0, 0.01}};
  err.labels = {"sea_nz=4, sea_nd=128", "sea_nz=8, sea_nd=128", "sea_nz=12, sea_nd=128", "sea_nz=24, sea_nd=128"};
  sweep.series = {err};
  plots.push_back(sweep);
  PlotSpec steps;
  steps.title = "Difference to the next setting: underwater_regions_open_water_with_objects";
  steps.x_label = "quality.source_streams";
  steps.y_label = "max difference (8-bit levels)";
  steps.log_y = true;
  steps.series = {line("max |L(v) - L(next v)| (8-bit levels)", 4, 1), {"1 level (1/255)", {3, 24}, {1, 1}}};
  plots.push_back(steps);
  PlotSpec ocean;
  ocean.title = "Ocean frame (evolve + 4 batched FFTs + all maps)";
  ocean.x_label = "grid N (N x N)";
  ocean.y_label = "ms per frame (median of 5)";
  ocean.log_x = ocean.log_y = true;
  ocean.series = {line("OpenCL + VkFFT (" + device + ")", 4, 1), line("C++/TBB + FFTW float (1 thread FFT)", 4, 3)};
  plots.push_back(ocean);
  PlotSpec pdf;
  pdf.title = "Caustic intensity PDF (004 §5.2.1, Figure 29)";
  pdf.x_label = "I / <I>";
  pdf.y_label = "probability density";
  pdf.log_y = true;
  pdf.series = {line("depth 0.5 m", 6, 1e-3), line("depth 2 m", 6, 1e-2), line("depth 10 m", 6, 1e-1)};
  plots.push_back(pdf);
  PlotSpec shore;
  shore.title = "Second order vs floor depth z_Q: seashore (320x180, floor ranges 2.5, 5, 12.5 m, " + device + ")";
  shore.x_label = "z_Q, depth where the view ray meets the floor (m; bin means)";
  shore.y_label = "ratio";
  for (const char* d : {"2.5", "5", "12.5"}) {
    shore.series.push_back(line(std::string("L2/L1, floor to ") + d + " m", 5, 0.1));
    shore.series.push_back(line(std::string("L2 share of water-leaving, floor to ") + d + " m", 5, 0.05));
  }
  plots.push_back(shore);
  PlotSpec study;
  study.title = "Spectral vs RGB against the path tracer (mean over cameras)";
  study.x_label = "Jerlov water type, seabed depth";
  study.y_label = "RMSE (8-bit levels); hue+sat distance x100";
  for (const char* w : {"I", "IA", "IB", "II", "III", "1C", "3C", "5C", "7C", "9C"})
    for (const char* d : {"2", "5", "10", "20", "40"}) study.x_categories.push_back(std::string(w) + ", " + d + " m");
  for (const char* m : {"spectral RMSE", "spectral hue+sat x100", "rgb RMSE", "rgb hue+sat x100"}) {
    PlotSeries s{m, {}, {}};
    for (size_t i = 0; i < study.x_categories.size(); ++i) s.x.push_back(double(i)), s.y.push_back(1.0 + i % 7);
    study.series.push_back(s);
  }
  plots.push_back(study);
  return plots;
}

TEST(SvgLayout, EveryTextOfEveryCommandPlotLiesInsideTheCanvas) {
  for (const std::string& device : {std::string("cpu"), kPocl, kLong}) {
    for (const PlotSpec& spec : commandPlots(device)) {
      const std::string svg = renderSvgPlot(spec);
      EXPECT_GT(seasim_test::svgTextBoxes(svg).size(), 5u) << spec.title;
      const auto bad = seasim_test::textOutsideCanvas(svg);
      EXPECT_TRUE(bad.empty()) << spec.title << ": " << bad.size() << " text(s) outside, first " << bad.front();
    }
  }
}

TEST(SvgLayout, TheCheckCatchesTextThatLeavesTheCanvas) {
  // The check itself: a title wider than the canvas, as the fixed layout wrote it, is reported.
  const std::string svg =
      "<svg width=\"800\" height=\"500\"><text x=\"360\" y=\"26\" font-size=\"16\" text-anchor=\"middle\" "
      "font-weight=\"bold\">Kernel time vs wavelength count (pthread-skylake-avx512-AMD EPYC 7B13 64-Core "
      "Processor)</text></svg>";
  EXPECT_EQ(seasim_test::textOutsideCanvas(svg).size(), 1u);
  const std::string rotated =
      "<svg width=\"800\" height=\"500\"><text x=\"0\" y=\"0\" font-size=\"13\" text-anchor=\"middle\" "
      "transform=\"translate(20 250) rotate(-90)\">a y label far longer than the five hundred pixels of the canvas's "
      "height, as no axis should have</text></svg>";
  EXPECT_EQ(seasim_test::textOutsideCanvas(rotated).size(), 1u);
}

std::vector<std::string> textsOfClass(const std::string& svg, const std::string& cls) {
  std::vector<std::string> out;
  const std::regex re("<text class=\"" + cls + "\"[^>]*>(.*?)</text>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back(svgPlainText((*it)[1].str()));
  return out;
}

TEST(SvgLayout, LongTitleShrinksThenWrapsKeepingEveryWord) {
  const PlotSpec spec = commandPlots(kLong).front();
  const auto lines = textsOfClass(renderSvgPlot(spec), "title");
  EXPECT_GE(lines.size(), 2u) << "a 100-character title does not fit 780 px at 12 px bold on one line";
  std::string joined;
  for (const auto& l : lines) joined += (joined.empty() ? "" : " ") + l;
  EXPECT_EQ(joined, spec.title);
  // A short title stays one line at its full size.
  PlotSpec small;
  small.title = "Error vs time";
  EXPECT_EQ(textsOfClass(renderSvgPlot(small), "title"), std::vector<std::string>{"Error vs time"});
  EXPECT_NE(renderSvgPlot(small).find("font-size=\"16\" text-anchor=\"middle\">Error vs time"), std::string::npos);
}

TEST(SvgLayout, SweepPointsCarryTheirKnobValues) {
  const PlotSpec spec = commandPlots("cpu")[2];
  EXPECT_EQ(textsOfClass(renderSvgPlot(spec), "point"), spec.series[0].labels);
}

TEST(SvgLayout, PointLabelsOfNearbyPointsDoNotOverlap) {
  PlotSpec spec;
  PlotSeries s{"rmse", {0.140, 0.1402, 0.1404, 0.151, 0.160}, {1.0, 1.0, 1.0, 1.0, 1.0}};
  s.labels = {"sea_nz=8", "sea_nz=12", "sea_nz=16", "sea_nz=24", "sea_nz=4"};
  spec.series.push_back(s);
  const std::string svg = renderSvgPlot(spec);
  std::vector<seasim_test::TextBox> points;
  for (const auto& b : seasim_test::svgTextBoxes(svg))
    if (b.text.rfind("sea_nz=", 0) == 0) points.push_back(b);
  ASSERT_EQ(points.size(), 5u);
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = i + 1; j < points.size(); ++j) {
      const auto &a = points[i], &b = points[j];
      EXPECT_FALSE(a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1) << a.text << " overlaps " << b.text;
    }
}

TEST(SvgLayout, CategoricalAxisTicksEachCategoryAndDrawsNoLines) {
  PlotSpec spec;
  spec.x_categories = {"IB, 5 m", "IB, 20 m", "3C, 5 m"};
  spec.series.push_back({"spectral RMSE", {0, 1, 2}, {1.0, 2.0, 4.0}});
  const std::string svg = renderSvgPlot(spec);
  EXPECT_EQ(textsOfClass(svg, "xtick"), spec.x_categories);
  EXPECT_EQ(svg.find("<polyline"), std::string::npos) << "nothing lies between two categories";
  EXPECT_TRUE(seasim_test::textOutsideCanvas(svg).empty());
}

TEST(SvgText, WidthIsDejaVuSansAdvances) {
  // "Wave" in DejaVu Sans Book: W 989 + a 613 + v 592 + e 616 = 2810 / 1000 em.
  EXPECT_NEAR(svgTextWidth("Wave", 10), 28.10, 1e-9);
  EXPECT_NEAR(svgTextWidth("Wave", 10, true), (1104 + 675 + 652 + 679) / 100.0, 1e-9);
  EXPECT_NEAR(svgTextWidth("§θ", 12), 24.0, 1e-9) << "non-ASCII: 1 em per character, not per byte";
  const auto lines = wrapSvgText("one two three four", 12, svgTextWidth("one two", 12));
  EXPECT_EQ(lines, (std::vector<std::string>{"one two", "three", "four"}));
  const auto broken = wrapSvgText("abcdefghij", 10, svgTextWidth("abcd", 10));
  ASSERT_GE(broken.size(), 3u);
  for (const auto& l : broken) EXPECT_LE(svgTextWidth(l, 10), svgTextWidth("abcd", 10));
  EXPECT_EQ(svgPlainText("10<tspan dy=\"-7\">3</tspan> &amp; &lt;m&gt;"), "103 & <m>");
}

}  // namespace
}  // namespace seasim
