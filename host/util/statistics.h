// statistics.h — summary statistics the benchmark commands print.
#pragma once
#include <algorithm>
#include <vector>

namespace seasim {

// The median of timings (the upper one of the middle two for an even count); 0 for none.
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace seasim
