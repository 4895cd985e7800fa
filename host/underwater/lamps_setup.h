// lamps_setup.h — the spotlights of an underwater scene as the kernels read them
// (common/underwater_lamps_params.h): one UwLamp per [[spotlights]] table and its spectral intensity
// per band (spectral/lamp_spectrum.h). Shared by the fast pass (passes/underwater_lamps_pass.h) and
// the path tracer (reference/underwater_reference.h), so both light the same lamps.
#pragma once
#include <vector>

#include "scene/scene.h"
#include "spectral/wavelength_grid.h"

extern "C" {
#include "common/underwater_lamps_params.h"
}

namespace seasim {

struct UnderwaterLamps {
  UwLampParams params{};       // lamp_count, band_count, s_min; planes/subplanes left 0 (the pass sets them)
  std::vector<UwLamp> lamps;   // at least one entry (OpenCL buffers cannot be empty)
  std::vector<float> spectra;  // [lamp * band_count + band], W sr^-1 nm^-1 on the axis; at least one entry
};

UnderwaterLamps makeUnderwaterLamps(const Scene& scene, const WavelengthGrid& grid);

}  // namespace seasim
