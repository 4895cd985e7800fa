// scene_facts.h — the facts about a scene that several models' plan rules decide on (where the
// camera is, whether the sun is up, which caustics): written once so that the rules agree.
#pragma once
#include "scene/scene.h"

namespace seasim {

// The camera is below the water's surface (the underwater frame, paper 002).
bool cameraUnderwater(const Scene& scene);
// The water is seen from above (the sea of paper 000, or [shallow]'s four-flow model).
bool seaSeenFromAbove(const Scene& scene);
// FFT waves on the water's surface (paper 004).
bool fftWaves(const Scene& scene);
// Spotlights in a scene without water (under water they are the underwater lamps).
bool spotlightsInAir(const Scene& scene);
// The sun is on, gives light, and is above the horizon.
bool sunUp(const Scene& scene);
// SEASIM_CAUSTICS of the underwater kernels: 0 none (or the sun down), 1 texture, 2 the ocean's map.
int underwaterCausticsMode(const Scene& scene);
// The FFT ocean runs for the underwater caustic maps (under water the model's surface is
// otherwise flat, so texture caustics or none need no ocean).
bool oceanForUnderwaterCaustics(const Scene& scene);
// The FFT ocean runs for the sea's wave normals ([shallow] averages its waves on the host, 003 eq. 10).
bool oceanForSea(const Scene& scene);
// The ocean's caustics on a sea bottom the sun reaches, seen from above (sea.bottom_caustics).
bool seaBottomCausticsPlanned(const Scene& scene);
// The discrete-ordinates underwater model's point-spread: the light delta-M counts as unscattered,
// put back blurred. Only that model scales by delta-M, and only a forward phase (g > 0) has a peak.
bool underwaterPointSpread(const Scene& scene);
// The model of the lamps under water, quality.lamps_model: "single", "delta_m" or "orders" (the parser's
// default). A scene built in code without it keeps its older switch lamps_delta_m's meaning where that is
// there, else the parser's default.
const char* underwaterLampsModel(const Scene& scene);
// SEASIM_SKY_MODEL (common/sky.h): 0 uniform, 1 analytic (CIE clear sky), 2 lat-long image, 3 Preetham.
int skyModelOf(const SkyDesc& sky);

}  // namespace seasim
