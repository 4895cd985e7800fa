// underwater_frame.h — what the underwater frame's nodes share (paper 002): the resources they publish
// as buffers ("gbuffer" of raycast.cl, "forward_light" of kd_multiple.cl; "underwater_setup" is
// passes/underwater_setup_buffers.h), the scene keys the underwater set-up folds in, and the
// "caustic_map" buffer the caustics node writes under water.
#pragma once
#include <CL/opencl.hpp>

#include <string>
#include <vector>

#include "render/resources.h"

namespace seasim {

// raycast.cl's G-buffer, per pixel of the camera's image.
struct UnderwaterGBuffer {
  cl::Buffer geometry;    // float4 (S, n): hit distance and normal
  cl::Buffer material;    // int: object index or UW_MAT_*
  cl::Buffer visibility;  // float: shadow ray × caustic factor
};

// The forward light kd_multiple.cl keeps apart for the water's point-spread (kernels/water_spread.cl;
// layouts in common/water_spread_params.h): [pixel][2][3] in sensor RGB, [pixel][2] its light-weighted
// distance and, with spectral output, [pixel][2][band_count] (else a null buffer).
struct UnderwaterForwardLight {
  cl::Buffer rgb, depth, spectral;
};

// Everything the underwater setup folds in: a change reruns the kernels with new parameter blocks.
inline const std::vector<std::string> kUnderwaterSetupKeys = {
    "sun.*",     "sky.*",     "water.*",  "bottom.*", "surface.*", "underwater.*",
    "objects.*", "quality.caustic_map_size", "quality.caustic_layers"};

// sand_share.cl's lattice: the discrete-ordinates model's shares that the objects leave, of the sunlit and of
// the diffusely lit sand's light and of the light from above, at every step-th pixel in x and y, three planes
// of width x height (kd_multiple.cl interpolates them).
struct UnderwaterSandShare {
  cl::Buffer map;
  int width = 0, height = 0, step = 1;
};

// The "caustic_map" buffer of the caustics pass when `res` declares reading it, else null.
const cl::Buffer* underwaterCausticMaps(PassResources& res);

}  // namespace seasim
