// fourflow_auto.h — quality.fourflow_table_size = "auto": the smallest (l, h) table resolution whose
// interpolation error is under a budget, like sea_lut_size's auto. Host, double, no rendering: the
// table of size n is built with the kernels' own ff_table_cell (kmath_d) and its blend (eq. 22, both
// bottom materials) is compared at every cell centre with the blend of cells evaluated exactly there.
// What it bounds is the table's interpolation error; the model error of eq. 22 against the exact
// path (eq. 20) does not shrink with n and is what `seasim sweep` measures (results/shallow/).
#pragma once
#include <vector>

#include "common/fourflow_params.h"

namespace seasim {

struct FourFlowTableChoice {
  int size = 0;
  double error = 0;  // worst |Δ| over cell centres and channels, relative to the brightest blend value
};

// Sizes 8, 16, 32, ... up to max_size; the first with error <= budget, else max_size.
// `params` gives the ranges, γ and the materials (its n_l, n_h are ignored).
FourFlowTableChoice chooseFourFlowTableSize(const std::vector<FfBand>& bands, const FfParams& params,
                                            double budget = 1.0 / 1024, int max_size = 256);

}  // namespace seasim
