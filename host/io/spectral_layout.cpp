// spectral_layout.cpp — formatting and parsing with std::to_chars / std::from_chars, so the
// decimal separator never depends on the C locale.
#include "io/spectral_layout.h"

#include <charconv>
#include <cmath>
#include <string_view>

#include "util/error.h"

namespace seasim {

std::string spectralChannelName(double wavelength_nm) {
  if (!std::isfinite(wavelength_nm) || wavelength_nm <= 0.0)
    throw RuntimeError("spectral EXR: wavelength " + std::to_string(wavelength_nm) +
                       " nm is not a positive finite number");
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, wavelength_nm, std::chars_format::fixed, 6);
  std::string value(buf, res.ptr);
  for (char& ch : value)
    if (ch == '.') ch = ',';
  return "S0." + value + "nm";
}

std::string spectralLayerChannelName(const std::string& layer, double wavelength_nm) {
  return layer + "." + spectralChannelName(wavelength_nm);
}

bool parseSpectralChannelName(const std::string& name, double& wavelength_nm) {
  std::string_view s(name);
  if (s.substr(0, 3) != "S0.") return false;
  s.remove_prefix(3);
  // Unit: metres or hertz, then an optional SI prefix before it.
  bool hertz = false;
  if (s.size() >= 2 && s.substr(s.size() - 2) == "Hz") {
    hertz = true;
    s.remove_suffix(2);
  } else if (!s.empty() && s.back() == 'm') {
    s.remove_suffix(1);
  } else {
    return false;
  }
  // Powers of ten; wavelengths are scaled straight to nm (10^(e+9)) so that "S0.550,000000nm"
  // parses to exactly 550.
  struct Prefix { std::string_view text; int exponent; };
  static constexpr Prefix kPrefixes[] = {
      {"da", 1}, {"Y", 24}, {"Z", 21}, {"E", 18}, {"P", 15}, {"T", 12}, {"G", 9}, {"M", 6},
      {"k", 3},  {"h", 2},  {"d", -1}, {"c", -2}, {"m", -3}, {"u", -6}, {"n", -9}, {"p", -12}};
  int exponent = 0;
  for (const Prefix& p : kPrefixes) {
    if (s.size() > p.text.size() && s.substr(s.size() - p.text.size()) == p.text) {
      exponent = p.exponent;
      s.remove_suffix(p.text.size());
      break;
    }
  }
  std::string number(s);
  for (char& ch : number)
    if (ch == ',') ch = '.';
  double value = 0.0;
  const auto res = std::from_chars(number.data(), number.data() + number.size(), value);
  if (res.ec != std::errc() || res.ptr != number.data() + number.size() || !(value > 0.0)) return false;
  if (hertz) {
    wavelength_nm = 299792458.0e9 / (value * std::pow(10.0, exponent));
  } else {
    const int e = exponent + 9;
    wavelength_nm = e >= 0 ? value * std::pow(10.0, e) : value / std::pow(10.0, -e);
  }
  return std::isfinite(wavelength_nm) && wavelength_nm > 0.0;
}

}  // namespace seasim
