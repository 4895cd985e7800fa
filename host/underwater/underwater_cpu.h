// underwater_cpu.h — the underwater frame's G-buffer and K_d shading (kernels/raycast.cl +
// kd_multiple.cl without the froxel term) evaluated on the CPU with the same shared math
// (kernels/common/underwater.h), in double (the reference the kernels are tested against) or float,
// with oneTBB over rows: the "plain C++/TBB implementation" the benchmark compares OpenCL against.
#pragma once
#include "io/image.h"
#include "underwater/underwater_setup.h"

namespace seasim {

struct UnderwaterCpuOptions {
  bool use_double = true;
  bool multiple = true;   // L_MS (SEASIM_HAS_MULTIPLE)
  bool single_split = false;  // as with SEASIM_HAS_FROXEL: L_MS and L_s leave out the direct beam
  bool parallel = true;   // oneTBB over rows; false runs on the calling thread
};

// Linear sensor RGB per pixel (3 channels). Caustics are not evaluated here (visibility = the exact
// shadow ray only): compare kernels with caustics off.
Image renderUnderwaterCpu(const UnderwaterSetup& setup, const UnderwaterCpuOptions& options);

}  // namespace seasim
