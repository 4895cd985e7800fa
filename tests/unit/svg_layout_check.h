// svg_layout_check.h — for the plot tests: the box of every <text> in an SVG written by
// io/svg_plot.h, and the ones that leave the canvas.
//
// A box is the text's advance width by io/svg_text.h (DejaVu Sans, an upper bound for the faces a
// browser picks for sans-serif) placed by its text-anchor, from ascent to descent of its font size;
// a superscript <tspan dy="-7"> raises the top by 7 px (its smaller digits are measured at the
// parent's size, which only widens the box). "translate(X Y) rotate(-90)" turns the box a quarter.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "io/svg_text.h"

namespace seasim_test {

struct TextBox {
  std::string text;
  double x0, y0, x1, y1;
};

inline double svgAttr(const std::string& attrs, const std::string& name, double fallback) {
  const std::regex re("\\b" + name + "=\"([-0-9.e]+)\"");
  std::smatch m;
  return std::regex_search(attrs, m, re) ? std::stod(m[1].str()) : fallback;
}

// Every <text> element's box; an element without x, y or font-size is a test failure (the writer
// promises each carries them).
inline std::vector<TextBox> svgTextBoxes(const std::string& svg) {
  std::vector<TextBox> boxes;
  const std::regex text_re("<text([^>]*)>(.*?)</text>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), text_re); it != std::sregex_iterator(); ++it) {
    const std::string attrs = (*it)[1].str(), body = (*it)[2].str();
    const double nan = std::nan("");
    const double x = svgAttr(attrs, "x", nan), y = svgAttr(attrs, "y", nan), size = svgAttr(attrs, "font-size", nan);
    EXPECT_TRUE(std::isfinite(x) && std::isfinite(y) && std::isfinite(size)) << "text without x, y or font-size: " << attrs;
    if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(size))) continue;
    const bool bold = attrs.find("font-weight=\"bold\"") != std::string::npos;
    const std::string plain = seasim::svgPlainText(body);
    const double w = seasim::svgTextWidth(plain, size, bold);
    double lx0 = x, lx1 = x + w;
    if (attrs.find("text-anchor=\"middle\"") != std::string::npos) lx0 = x - w / 2, lx1 = x + w / 2;
    if (attrs.find("text-anchor=\"end\"") != std::string::npos) lx0 = x - w, lx1 = x;
    double ly0 = y - 0.93 * size - (body.find("dy=\"-7\"") != std::string::npos ? 7.0 : 0.0), ly1 = y + 0.24 * size;
    std::smatch m;
    if (std::regex_search(attrs, m, std::regex("transform=\"translate\\(([-0-9.e]+) ([-0-9.e]+)\\) rotate\\(-90\\)\""))) {
      const double tx = std::stod(m[1].str()), ty = std::stod(m[2].str());
      boxes.push_back({plain, tx + ly0, ty - lx1, tx + ly1, ty - lx0});  // (u, v) -> (tx + v, ty - u)
    } else {
      EXPECT_EQ(attrs.find("transform"), std::string::npos) << "a transform the check does not know: " << attrs;
      boxes.push_back({plain, lx0, ly0, lx1, ly1});
    }
  }
  return boxes;
}

// The canvas size from the <svg width height>.
inline std::pair<double, double> svgCanvas(const std::string& svg) {
  const size_t at = svg.find("<svg ");
  const std::string head = at == std::string::npos ? "" : svg.substr(at, svg.find('>', at) - at);
  return {svgAttr(head, "width", 0), svgAttr(head, "height", 0)};
}

// Descriptions of the text boxes that are not inside the canvas; empty when every text fits.
inline std::vector<std::string> textOutsideCanvas(const std::string& svg) {
  const auto [w, h] = svgCanvas(svg);
  std::vector<std::string> bad;
  if (!(w > 0 && h > 0)) return {"no canvas size in <svg>"};
  for (const TextBox& b : svgTextBoxes(svg))
    if (b.x0 < 0 || b.y0 < 0 || b.x1 > w || b.y1 > h)
      bad.push_back("'" + b.text + "' [" + std::to_string(b.x0) + ", " + std::to_string(b.y0) + "] - [" +
                    std::to_string(b.x1) + ", " + std::to_string(b.y1) + "]");
  return bad;
}

}  // namespace seasim_test
