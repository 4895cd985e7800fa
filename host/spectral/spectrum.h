// spectrum.h — a sampled spectrum: values at increasing wavelengths (nm), linear in between,
// clamped to the end values outside the sampled range.
#pragma once
#include <string>
#include <vector>

namespace seasim {

struct Spectrum {
  std::vector<double> wavelengths_nm;  // strictly increasing
  std::vector<double> values;

  static Spectrum constant(double v) { return Spectrum{{550.0}, {v}}; }
  bool empty() const { return values.empty(); }
  // Piecewise-linear value at lambda_nm; end values held outside the range. 0 for an empty spectrum.
  double at(double lambda_nm) const;
};

}  // namespace seasim
