// lamps_setup.h — the spotlights of an underwater scene as the kernels read them
// (common/underwater_lamps_params.h): one UwLamp per [[spotlights]] table and its spectral intensity
// per band (spectral/lamp_spectrum.h). Shared by the fast pass (passes/underwater_lamps_pass.h) and
// the path tracer (reference/underwater_reference.h), so both light the same lamps.
#pragma once
#include <vector>

#include "scene/scene.h"
#include "underwater/underwater_setup.h"
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

// Delta-M scaling of a Henyey–Greenstein medium (Wiscombe 1977, "The delta-M method", J. Atmos. Sci.
// 34): the fraction f = g² of the scattered light in the forward peak is treated as not scattered at
// all, so σ_s' = σ_s (1 − f), σ_t' = σ_a + σ_s', and the rest keeps the phase function HG(g'),
// g' = (g − f)/(1 − f) = g/(1 + g). Single scattering in the scaled medium carries the light that is
// scattered a few degrees and goes on along the beam, which single scattering in the real medium
// counts as lost. g <= 0 has no forward peak: unchanged. Rewrites b, c per band and params.g.
void deltaMScale(UwParams& params, std::vector<UwBand>& bands);

}  // namespace seasim
