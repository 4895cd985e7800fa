// wavelength_grid.cpp — n equal bands, sampled at their centres (002 eq. 4.8).
#include "spectral/wavelength_grid.h"

#include <cmath>
#include <string>

#include "util/error.h"

namespace seasim {

WavelengthGrid makeGrid(int count, double min_nm, double max_nm) {
  if (count < 1 || count > 1000)
    throw RuntimeError("wavelength grid: band count must be 1..1000, got " + std::to_string(count));
  if (!std::isfinite(min_nm) || !std::isfinite(max_nm) || !(min_nm > 0.0) || !(max_nm > min_nm))
    throw RuntimeError("wavelength grid: need 0 < min_nm < max_nm, got [" + std::to_string(min_nm) + ", " +
                       std::to_string(max_nm) + "] nm");
  WavelengthGrid g;
  const double w = (max_nm - min_nm) / count;
  g.centers_nm.resize(static_cast<std::size_t>(count));
  g.widths_nm.assign(static_cast<std::size_t>(count), w);
  // min + (i + 1/2) w rather than a running sum, so the last centre has no accumulated rounding.
  for (int i = 0; i < count; ++i) g.centers_nm[static_cast<std::size_t>(i)] = min_nm + (i + 0.5) * w;
  return g;
}

}  // namespace seasim
