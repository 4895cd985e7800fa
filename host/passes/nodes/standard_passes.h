// standard_passes.h — the registry of every pass seasim ships, by plan name (plan/plan.cpp). Each
// node wraps the pass class of its kernel file (host/passes/*_pass.h) in the renderer's Pass
// interface (render/pass.h): it says which scene keys it depends on, sets the class up in prepare()
// and runs it in execute(). A new model adds its node here and a plan rule.
#pragma once
#include <CL/opencl.hpp>

#include "passes/auto_quality.h"
#include "render/pass_registry.h"

namespace seasim {

// `auto_quality` chooses the settings of "auto" quality knobs (passes/auto_quality.h); the default
// gives them their placeholders. Commands use quality/auto_quality.h's shippedPasses(), which searches.
PassRegistry standardPasses(const AutoQuality& auto_quality = {});

// One registration per file of this folder.
void registerOceanPass(PassRegistry& registry);      // ocean_fft
void registerCausticsPass(PassRegistry& registry);   // caustics (sea bottom, or under water)
void registerSeaPasses(PassRegistry& registry, const AutoQuality& auto_quality);  // sea_single, sea_second
void registerUnderwaterPasses(PassRegistry& registry);  // raycast (raycast.cl), froxel, kd_multiple, underwater_lamps
void registerShaftsPasses(PassRegistry& registry, const AutoQuality& auto_quality);  // raycast (shafts.cl), shadow_maps, shafts
void registerFourFlowPass(PassRegistry& registry);   // fourflow (shallow water, paper 003)
void registerCheckPass(PassRegistry& registry);      // nonfinite_check

// Under water, the "caustic_map" buffer of the caustics pass when `res` declares reading it, else null.
const cl::Buffer* underwaterCausticMaps(PassResources& res);

}  // namespace seasim
