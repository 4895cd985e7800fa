#include "math/linear_solve.h"

#include <cmath>
#include <utility>

namespace seasim {

bool solveLinear(std::vector<double>& a, std::vector<double>& rhs, int n, int columns) {
  const int m = columns;
  for (int col = 0; col < n; ++col) {
    int piv = col;
    for (int r = col + 1; r < n; ++r)
      if (std::abs(a[r * n + col]) > std::abs(a[piv * n + col])) piv = r;
    if (!(std::abs(a[piv * n + col]) > 0)) return false;
    if (piv != col) {
      for (int c = 0; c < n; ++c) std::swap(a[col * n + c], a[piv * n + c]);
      for (int k = 0; k < m; ++k) std::swap(rhs[col * m + k], rhs[piv * m + k]);
    }
    for (int r = col + 1; r < n; ++r) {
      const double f = a[r * n + col] / a[col * n + col];
      if (f == 0) continue;
      for (int c = col; c < n; ++c) a[r * n + c] -= f * a[col * n + c];
      for (int k = 0; k < m; ++k) rhs[r * m + k] -= f * rhs[col * m + k];
    }
  }
  for (int k = 0; k < m; ++k)
    for (int r = n - 1; r >= 0; --r) {
      double s = rhs[r * m + k];
      for (int c = r + 1; c < n; ++c) s -= a[r * n + c] * rhs[c * m + k];
      rhs[r * m + k] = s / a[r * n + r];
    }
  return true;
}

}  // namespace seasim
