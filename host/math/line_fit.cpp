#include "math/line_fit.h"

#include <stdexcept>

namespace seasim {

LineFit fitLine(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size() || x.size() < 2)
    throw std::invalid_argument("fitLine: needs x and y of the same size, at least 2 points");
  const double count = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  mx /= count, my /= count;
  // Centred sums: stable when x or y sits far from 0 (wavelength counts in the thousands).
  double sxy = 0, sxx = 0, syy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  LineFit fit;
  fit.slope = sxx > 0 ? sxy / sxx : 0;
  fit.intercept = my - fit.slope * mx;
  fit.r2 = sxx > 0 && syy > 0 ? sxy * sxy / (sxx * syy) : 1.0;
  return fit;
}

}  // namespace seasim
