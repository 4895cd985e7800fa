// underwater_setup_buffers.h — the underwater frame's shared set-up (002 §4): the host tables of
// makeUnderwaterSetup (camera, sun, water, bands, objects, sky, the band table) and the device copies
// that raycast.cl, kd_multiple.cl and geometry_layers.cl read. nodes/underwater_setup_node.cpp makes
// it and publishes it as "underwater_setup"; the passes that read it never build it.
#pragma once
#include <CL/opencl.hpp>

#include <cstddef>

#include "device/device.h"
#include "underwater/underwater_setup.h"

namespace seasim {

struct UnderwaterSetupBuffers {
  UnderwaterSetupBuffers(Device& device, UnderwaterSetup setup);
  // Writes a newer setup into the same buffers (a change of sun, water, time or knobs) and takes it;
  // false, with `newer` and the buffers untouched, when a size differs (bands, objects, sky, image or
  // the band table's rows): make new buffers from it then.
  bool update(Device& device, UnderwaterSetup&& newer);

  UnderwaterSetup setup;
  cl::Buffer params;      // UwParams
  cl::Buffer bands;       // UwBand per band
  cl::Buffer objects;     // UwObject per object
  cl::Buffer albedo;      // [object * band_count + band]
  cl::Buffer band_table;  // underwater/underwater_band_table.h
  cl::Buffer sky_params;  // SkyParams (common/sky_view.h)
  cl::Buffer sky;         // its image texels or Preetham's reals
  size_t band_table_floats = 0;
};

}  // namespace seasim
