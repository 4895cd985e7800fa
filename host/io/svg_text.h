// svg_text.h — how wide a line of SVG text is, without a font library, so the plot writer can lay
// text out and a test can check that no text leaves the canvas.
//
// The width is measured with DejaVu Sans's advance widths (regular and bold, ASCII 32-126, rounded
// up to 1/1000 em; read from the font's hmtx table with fontTools). DejaVu Sans is what
// `font-family="sans-serif"` resolves to on Debian and Ubuntu, and it is wider than the sans-serif
// faces other systems pick (Arial, Helvetica, Liberation Sans: 'a' 556 vs DejaVu's 613), so a layout
// that fits with these widths fits with those. Any character outside ASCII counts as 1 em, the
// widest advance of either face but the bold 'W' (1.104 em), so the measure stays an upper bound.
#pragma once
#include <string>
#include <vector>

namespace seasim {

// Width in px of `text` (UTF-8, no markup) at `font_size` px.
double svgTextWidth(const std::string& text, double font_size, bool bold = false);

// `text` broken at spaces into lines no wider than `max_width` px; a word wider than that on its
// own is broken between characters. Never returns an empty list ("" gives one empty line).
std::vector<std::string> wrapSvgText(const std::string& text, double font_size, double max_width, bool bold = false);

// The text of an SVG fragment with its markup removed and entities decoded (&amp; -> &).
std::string svgPlainText(const std::string& fragment);

}  // namespace seasim
