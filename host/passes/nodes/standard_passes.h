// standard_passes.h — the registry of every pass seasim ships: one factory per descriptor of
// passDescriptors() (plan/pass_descriptor.h; the list is nodes/pass_list.cpp). Each node wraps the
// pass class of its kernel file (host/passes/*_pass.h) in the renderer's Pass interface
// (render/pass.h) and registers its model's descriptor.
#pragma once
#include "passes/auto_quality.h"
#include "render/pass_registry.h"

namespace seasim {

// `auto_quality` chooses the settings of "auto" quality knobs (passes/auto_quality.h); the default
// gives them their placeholders. Commands use quality/auto_quality.h's shippedPasses(), which searches.
PassRegistry standardPasses(const AutoQuality& auto_quality = {});

}  // namespace seasim
