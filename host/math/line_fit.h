// line_fit.h — ordinary least squares of a straight line y = intercept + slope x, and how straight the
// points lie (R²): the benchmarks' cost models, time against wavelength count (002 §6.3) and against
// spotlight count (001 §5: "cost linear in the number of lights").
#pragma once
#include <vector>

namespace seasim {

struct LineFit {
  double intercept = 0;
  double slope = 0;
  double r2 = 1;  // squared correlation; 1 when x or y does not vary (a point, or a flat line)
};

// x and y of the same size >= 2 (throws std::invalid_argument otherwise). All x equal: slope 0 and the
// intercept the mean of y.
LineFit fitLine(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace seasim
