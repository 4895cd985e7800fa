// linear_solve.h — a small dense linear system a x = rhs by Gaussian elimination with partial pivoting
// (the discrete-ordinates solver's boundary and particular systems, the discrete-ordinates model's 3x3 fits).
#pragma once
#include <vector>

namespace seasim {

// a: n x n, row-major; rhs: n x columns, row-major (columns right-hand sides, one elimination for them
// all). a and rhs are overwritten and the solutions are left in rhs. Returns false (rhs then undefined)
// when a pivot is 0 or not finite: the system is singular.
bool solveLinear(std::vector<double>& a, std::vector<double>& rhs, int n, int columns = 1);

}  // namespace seasim
