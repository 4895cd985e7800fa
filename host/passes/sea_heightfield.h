// sea_heightfield.h — the height-field sea floor of 000 §5.4 on the host: [bottom] type = "heightfield"
// turned into the SeaHeightField block and depth nodes the kernels read (kernels/common/sea_bottom.h),
// their device buffers, and the on-disk cache of the second-order depth tables (sea_second.cl).
//
// Image -> floor: grey g in [0, 1] (the first channel, or the mean of R, G, B) gives the depth
// max_depth + g (min_depth - max_depth): 0 -> max_depth, 1 -> min_depth (scenes/README.md). Pixel
// (i, j) of a W x H image is node (i, j): x = -extent/2 + i extent/(W-1), z = -extent/2 + j extent/(H-1),
// the top row at z = -extent/2. Outside the square the border extends outwards.
#pragma once
#include <CL/opencl.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "device/device.h"
#include "scene/scene.h"

extern "C" {
#include "common/sea_bottom_params.h"
}

namespace seasim {

struct HeightField {
  SeaHeightField params{};   // as the kernels read it (min/max over the nodes, not the scene's keys)
  std::vector<float> depth;  // m, depth[j * nx + i]
};

// Reads bottom.heightfield. Throws RuntimeError naming the file when it cannot be read, is smaller
// than 2 x 2 or holds a non-finite value.
// files: read the image through it (io/data_files.h), or directly when null.
HeightField loadHeightField(const BottomDesc& bottom, DataFiles* files = nullptr);

// A floor from nodes already in memory (tests, tools): depth[j * nx + i] in m, >= 0.
HeightField makeHeightField(int nx, int ny, double extent, std::vector<float> depth);

struct HeightFieldBuffers {
  cl::Buffer params;  // one SeaHeightField (__constant)
  cl::Buffer depth;   // nx * ny floats
};
HeightFieldBuffers uploadHeightField(Device& device, const HeightField& field);
// The device bytes uploadHeightField allocates for `field` (the memory budget's estimate).
double heightFieldBytes(const HeightField& field);

// The second-order depth tables are a pure function of their inputs (floor, camera, map and
// direction settings, table nodes, kernel source), so they are cached on disk under
// $SEASIM_CACHE_DIR/sea_depth_tables/<key>.f32 (else $XDG_CACHE_HOME/seasim, ~/.cache/seasim) and
// computed once per scene; the shipped scenes' tables also come with the kernel store
// (device/kernel_store.h), read when the cache lacks them. `key` hashes everything they depend on.
// Best effort: a missing or unwritable cache only costs the computation.
std::optional<std::vector<float>> loadDepthTable(uint64_t key, size_t count);
void storeDepthTable(uint64_t key, const std::vector<float>& table);

}  // namespace seasim
