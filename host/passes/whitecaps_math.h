// whitecaps_math.h — kernels/common/whitecaps.h compiled for the host twice, as host/math/kernel_math.h
// does for the other models: seasim::whitecaps_f (real = float, what the kernel runs) and
// seasim::whitecaps_d (real = double, the CPU evaluation the tests compare the kernel with, and the
// host's Monahan coverage and foam reflectance).
#pragma once
#include <cmath>

#include "common/compat.h"
#include "common/whitecaps_params.h"

namespace seasim::whitecaps_f {
typedef float real;
#include "common/real3_host.h"
using std::ceil;
using std::floor;
using std::log2;
#include "common/whitecaps.h"
}  // namespace seasim::whitecaps_f

namespace seasim::whitecaps_d {
typedef double real;
#include "common/real3_host.h"
using std::ceil;
using std::floor;
using std::log2;
#include "common/whitecaps.h"
}  // namespace seasim::whitecaps_d
