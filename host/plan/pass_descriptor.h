// pass_descriptor.h — everything the rest of seasim knows about one model, kept beside its pass
// (host/passes/nodes/<model>_node.cpp), after Filament's addPass(setup, execute) and Mitsuba's
// self-describing plugins: its plan rule, the scene keys it depends on, its quality knobs and their
// defaults, its buffer estimate, its cost weight and its factory. The planner (makePlan), the memory
// budget, the shard balancer and the renderer's registry ask the descriptors; none of them names a
// model; nor does the scene parser, which reads the scene keys a descriptor declares. Adding a model =
// a node with its descriptor, and one line in the ordered list of host/passes/nodes/pass_list.cpp.
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "plan/memory_budget.h"
#include "plan/plan.h"
#include "scene/model_keys.h"
#include "scene/scene.h"

namespace seasim {

class Pass;
struct AutoQuality;

// Scene keys as written in files and --set: "sun.zenith_deg", "objects[1].center". A pattern is a
// key ("surface.time") or a section with ".*" ("sun.*"; "objects.*" covers every objects[i] key).
struct PassKeys {
  std::vector<std::string> rebuild_on;  // prepare + execute again
  std::vector<std::string> rerun_on;    // execute again with the same set-up
};

// A [quality] knob a model reads, with the default it plans, estimates and costs with.

// What a pass is to the commands that report on passes by kind (`seasim bench`, the studies), so that
// they ask for "the underwater shading" and name no model: descriptorFor(PassRole) gives its name.
enum class PassRole {
  None,
  SeaShading,                  // the sea seen from above, per pixel and band
  SeaSecondOrder,              // the sea's second order of scattering
  Spotlights,                  // spotlight shafts in air (its timing), after the shadow maps
  ShadowMaps,                  // the spotlights' shadow maps (their timing)
  UnderwaterGBuffer,           // the underwater frame's ray cast
  UnderwaterSingleScattering,  // the froxel single scattering (its kernels' timings start with its name)
  UnderwaterShading,           // the underwater frame's shading, per pixel and band
  UnderwaterLamps,             // the lamps' light in the water, added to the underwater frame
  Check,                       // a check on the frame, not part of its rendering time
};

struct PassDescriptor {
  std::string name;         // the plan entry's name
  std::string kernel_file;  // relative to kernels/ ("sea_single.cl")
  PassRole role = PassRole::None;

  // The plan rule: the entry this model adds for `scene`, given the passes planned before it
  // (`so_far`, in plan order); nullopt when the scene does not need it. makePlan gives the entry
  // the descriptor's name and kernel file and generates its defines from its features.
  std::function<std::optional<PassPlan>(const Scene& scene, const Plan& so_far)> rule;
  // The scene keys the pass depends on (render/pass.h: rebuild or rerun when one changes).
  PassKeys keys;
  // Its [quality] knobs; knob() and settledKnob() read only these.
  std::vector<KnobDefault> knobs;
  // Scene keys of its own (scene/model_keys.h: table, name, type, range, default): the parser reads
  // them from here, and the model reads them with modelKey(scene, "table.name").
  std::vector<ModelKey> scene_keys;
  // Whether quality.fast_math builds its kernel with -cl-fast-relaxed-math (false where the error
  // under relaxed maths was not measured, or where finite-only maths would hide what it checks).
  bool fast_math = true;
  // The big device buffers (and host copies) it allocates for `entry` (plan/memory_budget.h).
  std::function<std::vector<BufferEstimate>(const Scene& scene, const PassPlan& entry)> buffers;
  // Its cost per pixel and band relative to sea_single's at the default knobs, times how much more
  // the scene's knobs cost (jobs/shard_balance.h). Null: 1.
  std::function<double(const Scene& scene, const PassPlan& entry)> cost;
  // `seasim bench --limits`: the timing of the pass's band loop (a PassTiming name) and the loop's items
  // times bands in a frame of `bands` bands. Null: no band loop measured against the exp bound.
  std::string band_loop_timing;
  std::function<double(const Scene& scene, int bands)> band_loop_items;
  // Makes the renderer's pass for one entry of `plan` (render/pass_registry.h).
  std::function<std::unique_ptr<Pass>(const PassPlan& entry, const Plan& plan, const Scene& scene,
                                      const AutoQuality& auto_quality)>
      factory;

  // The knob's value in the scene (an "auto" knob's placeholder value), its default when absent.
  double knob(const Scene& scene, const char* name) const;
  // The same, but the default when the knob is "auto" or not positive: the search's pick is not
  // known before rendering.
  double settledKnob(const Scene& scene, const char* name) const;
};

// A plan rule's entry: what it reads and writes, why the scene needs it, its features.
PassPlan planEntry(std::vector<std::string> reads, std::vector<std::string> writes, std::string why,
                   std::shared_ptr<const PassFeatures> features = nullptr);

// Every shipped model, in plan order (host/passes/nodes/pass_list.cpp).
const std::vector<PassDescriptor>& passDescriptors();

// The descriptor that made `entry` (same name and kernel file), or null for an entry built by hand.
const PassDescriptor* descriptorOf(const PassPlan& entry);

// The first descriptor in plan order with `role`; throws when none has it.
const PassDescriptor& descriptorFor(PassRole role);

}  // namespace seasim
