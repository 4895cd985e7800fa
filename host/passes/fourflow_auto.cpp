// fourflow_auto.cpp — the "auto" table resolution of the four-flow pass (see the header).
#include "passes/fourflow_auto.h"

#include <algorithm>
#include <cmath>

#include "math/kernel_math.h"

namespace seasim {

namespace {

namespace kd = kmath_d;

// The blend of eq. 22 from one cell, for a bottom of material mix tex.
void blendCell(const FfParams& p, const double* cell, double tex, double* rgb) {
  for (int c = 0; c < 3; ++c) {
    const double t_bottom = (1 - tex) * p.rgb_a[c] + tex * p.rgb_b[c];
    rgb[c] = cell[3] * cell[c] * t_bottom + (1 - cell[3]) * cell[4 + c];
  }
}

double tableError(const std::vector<FfBand>& bands, FfParams p, int n) {
  p.n_l = p.n_h = n;
  std::vector<float> table(size_t(n) * n * FF_TABLE_STRIDE);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      double cell[FF_TABLE_STRIDE];
      kd::ff_table_cell(bands.data(), p.n_bands, p.gamma, kd::ff_table_l(p, i), kd::ff_table_h(p, j), cell);
      for (int q = 0; q < FF_TABLE_STRIDE; ++q) table[(size_t(j) * n + i) * FF_TABLE_STRIDE + q] = float(cell[q]);
    }
  double worst = 0, peak = 0;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      // The cell centre in the table's own coordinates (√l, h).
      const double t = (i + 0.5) / (n - 1);
      const double l = p.l_max * t * t, h = p.h_max * (j + 0.5) / (n - 1);
      double cell[FF_TABLE_STRIDE];
      kd::ff_table_cell(bands.data(), p.n_bands, p.gamma, l, h, cell);
      for (double tex : {0.0, 1.0}) {
        double exact[3], fast[3];
        blendCell(p, cell, tex, exact);
        kd::ff_table_rgb(p, table.data(), l, h, tex, 0, fast);
        for (int c = 0; c < 3; ++c) {
          worst = std::max(worst, std::fabs(fast[c] - exact[c]));
          peak = std::max(peak, std::fabs(exact[c]));
        }
      }
    }
  return peak > 0 ? worst / peak : 0.0;
}

}  // namespace

FourFlowTableChoice chooseFourFlowTableSize(const std::vector<FfBand>& bands, const FfParams& params, double budget,
                                            int max_size) {
  FourFlowTableChoice choice;
  for (int n = 8; n <= max_size; n *= 2) {
    choice.size = n;
    choice.error = tableError(bands, params, n);
    if (choice.error <= budget) break;
  }
  return choice;
}

}  // namespace seasim
