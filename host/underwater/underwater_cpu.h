// underwater_cpu.h — the underwater frame's G-buffer and K_d shading (kernels/raycast.cl +
// kd_multiple.cl without the froxel term) evaluated on the CPU with the same shared math
// (kernels/common/underwater.h), in double (the reference the kernels are tested against) or float,
// with oneTBB over rows: the "plain C++/TBB implementation" the benchmark compares OpenCL against.
#pragma once
#include <functional>

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

// rows(y0, y1) over [0, height): in blocks on oneTBB's threads when `parallel`, else in one call.
// The row loop both C++ evaluators share.
void forRowBlocks(int height, bool parallel, const std::function<void(int, int)>& rows);

// The same float frame shaped for the compiler's auto-vectoriser, the strong C++ peer of the
// OpenCL kernels in `seasim bench` (underwater_cpu_simd.cpp, built with -O3 -ffast-math
// -fopenmp-simd so GCC runs the band loops over 4/8/16 pixels at a time with libmvec's vector expf;
// results/underwater/peer_vectorisation.txt): per row, the G-buffer as arrays, the pixels sorted by
// what their ray hit, then per band straight loops over each group. options.use_double is ignored
// (float only); the image matches renderUnderwaterCpu's double one within the kernels' tolerance
// (tests/kernels/underwater_kd_test.cpp).
Image renderUnderwaterCpuSimd(const UnderwaterSetup& setup, const UnderwaterCpuOptions& options);

}  // namespace seasim
