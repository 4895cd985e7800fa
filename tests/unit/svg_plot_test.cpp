// svg_plot_test.cpp — host/io/svg_plot: document structure, ticks, legend, degenerate inputs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include "io/svg_plot.h"

namespace seasim {
namespace {

std::vector<std::string> tickLabels(const std::string& svg, const std::string& cls) {
  std::vector<std::string> out;
  const std::regex re("<text class=\"" + cls + "\"[^>]*>(.*?)</text>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back((*it)[1].str());
  return out;
}

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

// Cheap well-formedness check: every opened <g>, <svg> and <text> element is closed.
void expectBalanced(const std::string& svg) {
  EXPECT_EQ(svg.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg ", 0), 0u);
  EXPECT_EQ(count(svg, "<g"), count(svg, "</g>"));
  EXPECT_EQ(count(svg, "<svg"), count(svg, "</svg>"));
  EXPECT_EQ(count(svg, "<text"), count(svg, "</text>"));
  EXPECT_EQ(count(svg, "<tspan"), count(svg, "</tspan>"));
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
}

PlotSpec errorVsTime() {
  PlotSpec spec;
  spec.title = "Error vs time";
  spec.x_label = "time [ms]";
  spec.y_label = "RMSE [8-bit levels]";
  spec.log_x = spec.log_y = true;
  spec.series.push_back({"sea_second n_z", {0.5, 1.2, 3.0, 9.0, 40.0}, {20.0, 6.0, 1.5, 0.4, 0.003}});
  spec.series.push_back({"shafts <m> & \"planes\"", {0.8, 2.0, 7.0}, {15.0, 3.0, 0.9}});
  return spec;
}

TEST(SvgPlot, HeaderSeriesNamesAndLegend) {
  const std::string svg = renderSvgPlot(errorVsTime());
  expectBalanced(svg);
  EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_NE(svg.find(">sea_second n_z</text>"), std::string::npos);
  EXPECT_NE(svg.find(">shafts &lt;m&gt; &amp; &quot;planes&quot;</text>"), std::string::npos);  // escaped
  EXPECT_NE(svg.find(">Error vs time</text>"), std::string::npos);
  EXPECT_NE(svg.find(">time [ms]</text>"), std::string::npos);
  EXPECT_NE(svg.find(">RMSE [8-bit levels]</text>"), std::string::npos);
  EXPECT_EQ(count(svg, "class=\"series\""), 2u);
  EXPECT_NE(svg.find("#0072B2"), std::string::npos);  // distinct colours per series
  EXPECT_NE(svg.find("#D55E00"), std::string::npos);
}

TEST(SvgPlot, LogAxesTickAtDecades) {
  const std::string svg = renderSvgPlot(errorVsTime());
  // x 0.5 .. 40 -> decades 0.1 .. 100; y 0.003 .. 20 -> 0.001 .. 100.
  EXPECT_EQ(tickLabels(svg, "xtick"), (std::vector<std::string>{"0.1", "1", "10", "100"}));
  EXPECT_EQ(tickLabels(svg, "ytick"), (std::vector<std::string>{"0.001", "0.01", "0.1", "1", "10", "100"}));
  // Wide ranges switch to powers of ten.
  PlotSpec wide;
  wide.log_y = true;
  wide.series.push_back({"conv", {1, 2, 3}, {1e-9, 1e-4, 10.0}});
  const auto y = tickLabels(renderSvgPlot(wide), "ytick");
  ASSERT_EQ(y.size(), 11u);
  EXPECT_EQ(y.front(), "10<tspan dy=\"-7\" font-size=\"10\">-9</tspan>");
  EXPECT_EQ(y.back(), "10<tspan dy=\"-7\" font-size=\"10\">1</tspan>");
}

TEST(SvgPlot, LinearAxesUseNiceSteps) {
  PlotSpec spec;
  spec.x_label = "wavelengths";
  spec.series.push_back({"throughput", {1, 4, 8, 16, 32}, {0.05, 0.31, 0.52, 0.77, 0.93}});
  const std::string svg = renderSvgPlot(spec);
  expectBalanced(svg);
  EXPECT_EQ(tickLabels(svg, "xtick"), (std::vector<std::string>{"0", "5", "10", "15", "20", "25", "30", "35"}));
  EXPECT_EQ(tickLabels(svg, "ytick"), (std::vector<std::string>{"0.0", "0.2", "0.4", "0.6", "0.8", "1.0"}));
  PlotSpec big;
  big.series.push_back({"px/s", {0, 1}, {2.0e11, 1.3e12}});
  const auto yb = tickLabels(renderSvgPlot(big), "ytick");
  ASSERT_FALSE(yb.empty());
  EXPECT_EQ(yb.front(), "2e11");  // the axis spans the data, not down to 0
  EXPECT_EQ(yb.back(), "1.4e12");
}

TEST(SvgPlot, SinglePointEmptySeriesAndEmptyPlot) {
  PlotSpec one;
  one.series.push_back({"one", {3.0}, {7.0}});
  one.series.push_back({"empty", {}, {}});
  const std::string svg = renderSvgPlot(one);
  expectBalanced(svg);
  EXPECT_NE(svg.find(">one</text>"), std::string::npos);
  EXPECT_NE(svg.find(">empty</text>"), std::string::npos);
  EXPECT_EQ(count(svg, "<polyline"), 0u);  // one point draws a marker, no line
  EXPECT_FALSE(tickLabels(svg, "xtick").empty());
  PlotSpec one_log = one;
  one_log.log_x = one_log.log_y = true;
  expectBalanced(renderSvgPlot(one_log));
  const std::string none = renderSvgPlot(PlotSpec{});
  expectBalanced(none);
  EXPECT_NE(none.find(">no data</text>"), std::string::npos);
}

TEST(SvgPlot, NonFiniteAndNonPositiveOnLogPointsAreSkipped) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  PlotSpec spec;
  spec.log_y = true;
  spec.series.push_back({"gappy", {1, 2, 3, 4, 5, 6}, {1.0, 0.5, nan, 0.1, 0.0, 0.01}});
  const std::string svg = renderSvgPlot(spec);
  expectBalanced(svg);
  // Runs [1,2] and [4] and [6]: one polyline (a lone point draws no line), 4 markers + legend.
  EXPECT_EQ(count(svg, "<polyline"), 1u);
  EXPECT_EQ(count(svg, "<circle"), 4u + 1u);
  EXPECT_EQ(tickLabels(svg, "ytick"), (std::vector<std::string>{"0.01", "0.1", "1"}));
}

TEST(SvgPlot, WriteIsAtomic) {
  const auto dir = std::filesystem::temp_directory_path() / ("seasim_svg_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const std::string path = (dir / "plots/err.svg").string();
  writeSvgPlot(path, errorVsTime());
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), renderSvgPlot(errorVsTime()));
  std::size_t files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace seasim
