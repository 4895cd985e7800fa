// fourflow_reference.h — the brute-force reference of the four-flow model (paper 003 eq. 4 and 7): a
// double-precision numerical solve of the four linear ODEs as a two-point boundary-value problem, for
// the same constants and boundary coefficients as kernels/common/fourflow.h, sharing no formula with
// its closed form (no eigenvalues, no A1…A4, no C1…C4): only the ODE matrix and the boundary rows.
//
// Method: multiple shooting. [0, τ0] is cut into m equal segments of length <= max_segment; the
// propagator Φ of y' = M y over one segment (y = (G+, G-, F+, F-), M from 003 eq. 4) is built by
// classical RK4 (rk4_steps steps, applied to the four unit vectors); the unknowns are y at the m + 1
// nodes, tied by y_{i+1} = Φ y_i and by the four rows of 003 eq. 7, and solved together by banded
// Gaussian elimination with partial pivoting. Short segments keep every Φ entry within e^{±2}, so the
// growing and decaying solutions never meet in one number (single shooting over τ0 = 200 would need
// e^{200} - e^{200} cancellations); the RK4 error is about τ0 h⁴ / 120 relative (h the step).
#pragma once

#include <array>
#include <vector>

namespace seasim {

struct FourFlowBvp {
  // 003 eq. 4 constants.
  double k = 0, S = 0, S1 = 0, S2 = 0;
  double tau0 = 1;  // bottom at optical depth ε h
  // 003 eq. 7: surface (air->water T, water-side R "~") and bottom (R^) coefficients.
  double T_dd = 1, T_df = 0, T_ff = 1;
  double Rw_dd = 0, Rw_df = 0, Rw_ff = 0;
  double Rb_dd = 0, Rb_df = 0, Rb_ff = 0;
  double e_sun = 1, e_sky = 0;  // irradiance on a horizontal plane above the surface
};

struct FourFlowProfile {
  std::vector<double> tau;                  // node depths, 0 … τ0
  std::vector<std::array<double, 4>> flow;  // (G+, G-, F+, F-) at each node
};

// Numerical solution of 003 eq. 4 with eq. 7. max_segment is the longest shooting segment (optical
// depth), rk4_steps the RK4 steps per segment.
FourFlowProfile solveFourFlowBvp(const FourFlowBvp& p, double max_segment = 0.25, int rk4_steps = 32);

}  // namespace seasim
