// renderer.h — the persistent frame graph (DESIGN.md "The renderer's shape"). Built once per scene:
// the plan's entries become passes from the registry, which own their tables and buffers and publish
// the frame's named resources. render() runs the plan's passes in order through the Pass interface;
// the renderer knows no model by name.
//
// Incremental updates: update() names the scene keys that changed; a pass is set up again only when
// a key in its rebuild_on list changed or a resource it reads was replaced, and runs again only when
// it was set up, a key in its rerun_on list changed, or a resource it reads was written this frame.
// A pass that adds into a resource it reads (sea_second into "rgb") makes that resource's earlier
// writer run too, so nothing is added twice. A key that no pass of the plan claims, or a change that
// changes the plan, rebuilds everything (never a stale image).
#pragma once
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "device/device.h"
#include "plan/plan.h"
#include "render/frame_context.h"
#include "render/frame_result.h"
#include "render/pass.h"
#include "render/pass_registry.h"
#include "render/resources.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace seasim {

class Renderer {
 public:
  // The plan is makePlan(scene) — of the scene with the registry's plan choices made (a measured
  // shafts method) — made again when an update changes it.
  Renderer(Device& device, const Scene& scene, PassRegistry registry);
  // A fixed plan (tests build one by hand); update() keeps it.
  Renderer(Device& device, const Scene& scene, Plan plan, PassRegistry registry);
  // The scene file with its overrides, so that update(overrides) can read it again with more.
  Renderer(Device& device, const std::string& scene_file, std::vector<Override> overrides, PassRegistry registry);
  // The same from the scene's TOML text, named `scene_file` in messages and anchoring relative paths
  // (a scene that is no file: the Python package's Scene.from_dict).
  Renderer(Device& device, const std::string& scene_file, std::string scene_text, std::vector<Override> overrides,
           PassRegistry registry);

  // The scene after a change of the named keys ("surface.time", "sun.zenith_deg", "quality.froxel_x",
  // "objects[0].center"), as written in scene files and --set.
  void update(const Scene& next, const std::vector<std::string>& changed_keys);
  // Applies overrides on top of those given so far (the scene file's text, read once, is parsed and
  // validated again); keys whose value is what it was change nothing. Needs the scene-file constructor.
  void update(const std::vector<Override>& overrides);

  // Marks every pass to run again on the next render() with its current set-up (timing a whole
  // frame's kernels, as sweep and bench do).
  void rerunAll();

  // Runs the frame; throws RuntimeError for a pass that is not implemented or not registered, a
  // plan whose reads come before their writes; DeviceError on OpenCL failures.
  FrameResult render();

  const Plan& plan() const { return plan_; }
  const Scene& scene() const { return ctx_.scene(); }
  // Names of the passes set up / run by the last render(), in plan order.
  const std::vector<std::string>& lastPrepared() const { return last_prepared_; }
  const std::vector<std::string>& lastExecuted() const { return last_executed_; }

 private:
  Renderer(Device& device, const std::optional<Scene>& chosen, const Scene& scene, PassRegistry&& registry);

  struct Node {
    const PassPlan* entry = nullptr;
    std::unique_ptr<Pass> pass;
    PassKeys keys;
    bool prepared = false;
    bool rebuild = false;
    bool rerun = false;
    std::map<std::string, uint64_t> seen_generation, seen_version;  // of its reads, after it last ran
  };
  void build();
  std::vector<bool> passesToRun() const;
  bool readsReplaced(const Node& node) const;
  bool readsWritten(const Node& node) const;

  Device& device_;
  PassRegistry registry_;
  bool follow_scene_;  // plan = makePlan(scene) after each update
  Plan plan_;
  FrameContext ctx_;
  Resources resources_;
  std::vector<Node> nodes_;
  std::string scene_file_;
  std::string scene_text_;  // read once: an update parses it again with the new overrides
  std::vector<Override> overrides_;
  long long nonfinite_ = 0;
  std::vector<std::string> last_prepared_, last_executed_;
};

}  // namespace seasim
