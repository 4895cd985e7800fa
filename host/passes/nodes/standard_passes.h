// standard_passes.h — the registry of every pass seasim ships, by plan name (plan/plan.cpp). Each
// node wraps the pass class of its kernel file (host/passes/*_pass.h) in the renderer's Pass
// interface (render/pass.h): it says which scene keys it depends on, sets the class up in prepare()
// and runs it in execute(). A new model adds its node here and a plan rule.
#pragma once
#include <CL/opencl.hpp>

#include "render/pass_registry.h"

namespace seasim {

PassRegistry standardPasses();

// One registration per file of this folder.
void registerOceanPass(PassRegistry& registry);      // ocean_fft
void registerCausticsPass(PassRegistry& registry);   // caustics (sea bottom, or under water)
void registerSeaPasses(PassRegistry& registry);      // sea_single, sea_second
void registerUnderwaterPasses(PassRegistry& registry);  // raycast (raycast.cl), froxel, kd_multiple
void registerShaftsPasses(PassRegistry& registry);   // raycast (shafts.cl), shadow_maps, shafts
void registerFourFlowPass(PassRegistry& registry);   // fourflow (shallow water, paper 003)
void registerCheckPass(PassRegistry& registry);      // nonfinite_check

// Under water, the "caustic_map" buffer of the caustics pass when `res` declares reading it, else null.
const cl::Buffer* underwaterCausticMaps(PassResources& res);

}  // namespace seasim
