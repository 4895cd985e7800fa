#include "spectral/spectrum.h"

#include <algorithm>

namespace seasim {

double Spectrum::at(double lambda_nm) const {
  if (values.empty()) return 0.0;
  if (values.size() == 1 || lambda_nm <= wavelengths_nm.front()) return values.front();
  if (lambda_nm >= wavelengths_nm.back()) return values.back();
  auto hi = std::upper_bound(wavelengths_nm.begin(), wavelengths_nm.end(), lambda_nm);
  size_t i = static_cast<size_t>(hi - wavelengths_nm.begin());
  double t = (lambda_nm - wavelengths_nm[i - 1]) / (wavelengths_nm[i] - wavelengths_nm[i - 1]);
  return values[i - 1] + t * (values[i] - values[i - 1]);
}

}  // namespace seasim
