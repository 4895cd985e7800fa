#include "io/svg_text.h"

#include <algorithm>

namespace seasim {

namespace {

// DejaVu Sans Book and Bold advance widths of ASCII 32 (space) .. 126 ('~'), in 1/1000 em.
constexpr int kRegular[95] = {
    318, 401, 460, 838, 637, 951, 780, 275, 391, 391, 500, 838, 318, 361, 318, 337,  //
    637, 637, 637, 637, 637, 637, 637, 637, 637, 637, 337, 337, 838, 838, 838, 531,  //
    1000, 685, 687, 699, 771, 632, 576, 775, 752, 295, 295, 656, 558, 863, 749, 788,  //
    604, 788, 695, 635, 611, 732, 685, 989, 686, 611, 686, 391, 337, 391, 838, 500,  //
    500, 613, 635, 550, 635, 616, 353, 635, 634, 278, 278, 580, 278, 975, 634, 612,  //
    635, 635, 412, 521, 393, 634, 592, 818, 592, 592, 525, 637, 337, 637, 838};
constexpr int kBold[95] = {
    349, 457, 521, 838, 696, 1002, 873, 307, 458, 458, 523, 838, 380, 416, 380, 366,  //
    696, 696, 696, 696, 696, 696, 696, 696, 696, 696, 400, 400, 838, 838, 838, 581,   //
    1000, 774, 763, 734, 831, 684, 684, 821, 837, 373, 373, 775, 638, 996, 837, 851,  //
    733, 851, 771, 721, 683, 813, 774, 1104, 771, 725, 726, 458, 366, 458, 838, 500,  //
    500, 675, 716, 593, 716, 679, 436, 716, 712, 343, 343, 666, 343, 1042, 712, 688,  //
    716, 716, 494, 596, 479, 712, 652, 924, 646, 652, 583, 712, 366, 712, 838};

// Bytes of the UTF-8 sequence starting with `lead` (1 for ASCII and for stray continuation bytes).
int sequenceLength(unsigned char lead) {
  if (lead >= 0xF0) return 4;
  if (lead >= 0xE0) return 3;
  if (lead >= 0xC0) return 2;
  return 1;
}

}  // namespace

double svgTextWidth(const std::string& text, double font_size, bool bold) {
  const int* table = bold ? kBold : kRegular;
  long units = 0;
  for (size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 32 && c <= 126) {
      units += table[c - 32];
      ++i;
    } else {
      units += 1000;
      i += static_cast<size_t>(sequenceLength(c));
    }
  }
  return font_size * static_cast<double>(units) / 1000.0;
}

std::vector<std::string> wrapSvgText(const std::string& text, double font_size, double max_width, bool bold) {
  std::vector<std::string> lines;
  std::string line;
  auto fits = [&](const std::string& s) { return svgTextWidth(s, font_size, bold) <= max_width; };
  size_t i = 0;
  while (i <= text.size()) {
    const size_t space = std::min(text.find(' ', i), text.size());
    std::string word = text.substr(i, space - i);
    const std::string joined = line.empty() ? word : line + " " + word;
    if (fits(joined)) {
      line = joined;
    } else {
      if (!line.empty()) lines.push_back(line);
      line.clear();
      // A word too wide for a line of its own: break it between (UTF-8) characters.
      while (!fits(word)) {
        size_t cut = 0, next = 0;
        while (next < word.size() && fits(word.substr(0, next + sequenceLength(static_cast<unsigned char>(word[next])))))
          next += static_cast<size_t>(sequenceLength(static_cast<unsigned char>(word[next])));
        cut = std::max<size_t>(next, static_cast<size_t>(sequenceLength(static_cast<unsigned char>(word[0]))));
        lines.push_back(word.substr(0, cut));
        word = word.substr(cut);
      }
      line = word;
    }
    i = space + 1;
  }
  lines.push_back(line);
  return lines;
}

std::string svgPlainText(const std::string& fragment) {
  std::string out;
  bool in_tag = false;
  for (char c : fragment) {
    if (c == '<') in_tag = true;
    else if (c == '>') in_tag = false;
    else if (!in_tag) out += c;
  }
  const std::pair<const char*, const char*> entities[] = {
      {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&apos;", "'"}, {"&amp;", "&"}};
  for (const auto& [from, to] : entities)
    for (size_t p = out.find(from); p != std::string::npos; p = out.find(from, p + 1)) out.replace(p, std::string(from).size(), to);
  return out;
}

}  // namespace seasim
