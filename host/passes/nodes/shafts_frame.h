// shafts_frame.h — what the three plan entries on shafts.cl share (paper 001, passes/shafts_pass.h):
// "raycast" and "shadow_maps" name work that ShaftsPass::run does inside the shafts kernel's launch
// sequence (the per-pixel ray cast is in the shafts kernel itself; the shadow maps are enqueued just
// before it), so their nodes hold nothing; "shafts" (shafts_node.cpp) sets up and runs the pass.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "passes/shafts_features.h"
#include "plan/pass_descriptor.h"
#include "render/pass.h"

namespace seasim {

inline const PassKeys kShaftsKeys = {
    {"camera.*", "spotlights.*", "objects.*", "air.*", "spectral.*", "quality.shafts_exact", "quality.shafts_planes",
     "quality.shafts_subplanes", "quality.shafts_error_budget", "quality.shafts_table_size",
     "quality.shadow_map_size", "quality.shafts_method", "quality.shafts_panel_deg", "quality.shafts_panel_texels"},
    {}};

// The features of shafts.cl for `scene`, shared by the shadow_maps and shafts entries (one build).
std::shared_ptr<ShaftsFeatures> shaftsFeatures(const Scene& scene);

// An entry whose work the shafts node does.
class InsideShaftsNode : public Pass {
 public:
  PassKeys keys() const override { return kShaftsKeys; }
  void prepare(FrameContext&, PassResources&) override {}
  void execute(FrameContext&, PassResources&) override {}
};

}  // namespace seasim
