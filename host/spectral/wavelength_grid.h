// wavelength_grid.h — the n wavelength bands a spectral render evaluates.
//
// The range [min_nm, max_nm] is cut into n equal bands of width w = (max - min) / n and each band is
// evaluated at its centre (002 eq. 4.8: the rectangle rule with w = (max(λ) - min(λ)) / n; placing
// the sample at the band's centre makes it the midpoint rule, second-order accurate in w).
#pragma once
#include <cstddef>
#include <vector>

namespace seasim {

struct WavelengthGrid {
  std::vector<double> centers_nm;  // λ_i = min + (i + 1/2) w, increasing
  std::vector<double> widths_nm;   // Δλ_i = w for every band; they sum to max - min

  std::size_t size() const { return centers_nm.size(); }
  double minNm() const { return centers_nm.front() - 0.5 * widths_nm.front(); }
  double maxNm() const { return centers_nm.back() + 0.5 * widths_nm.back(); }
};

// count in 1..1000 (DESIGN.md), 0 < min_nm < max_nm, both finite. RuntimeError otherwise.
WavelengthGrid makeGrid(int count, double min_nm, double max_nm);

}  // namespace seasim
